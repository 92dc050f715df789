#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec spectrum`: reflectance / transmittance / absorptance spectra of skin with the BioSpec walk.
void add_spectrum_command(CLI::App& app);

}  // namespace skinspec::cli
