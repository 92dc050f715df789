#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec swatch`: a chart image of simulated skin colours over one or two stack fields.
void add_swatch_command(CLI::App& app);

}  // namespace skinspec::cli
