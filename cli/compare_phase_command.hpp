#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec compare-phase`: measured versus Henyey-Greenstein thin layers inside the BioSpec skin model.
void add_compare_phase_command(CLI::App& app);

}  // namespace skinspec::cli
