#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec fit-spectrum MEASURED.csv`: biophysical parameters of measured skin reflectance spectra, fitted with
// the BioSpec walk on replayed paths (inverse/spectrum_fit, docs/SPECTRUM_FIT.md).
void add_fit_spectrum_command(CLI::App& app);

}  // namespace skinspec::cli
