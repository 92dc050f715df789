#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec mcml FILE.mci`: MCML input files through the volumetric walk, MCML .mco output plus JSON.
void add_mcml_command(CLI::App& app);

}  // namespace skinspec::cli
