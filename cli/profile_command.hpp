#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec profile`: radial diffuse reflectance R(r) and transmittance T(r) of a material in a diffusion
// mode, per wavelength or band, as CSV and an optional log-scale plot.
void add_profile_command(CLI::App& app);

}  // namespace skinspec::cli
