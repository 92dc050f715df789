#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec bench`: run time against error for every solver (layers/benchmark/runtime_benchmark.hpp), the
// fitted error-time slopes, the Pareto front and the fastest solver for an error tolerance, thread scaling
// and the time per colour; tables on standard output, optional CSV, JSON and a log-log plot.
void add_bench_command(CLI::App& app);

}  // namespace skinspec::cli
