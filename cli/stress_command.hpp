#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec stress`: the stability suite's grid (layers/benchmark/stress_grid.hpp), short or full; one line
// per failing case or limit met, a summary, exit code 1 when a case fails.
void add_stress_command(CLI::App& app);

}  // namespace skinspec::cli
