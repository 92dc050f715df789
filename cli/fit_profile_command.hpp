#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec fit-profile`: subsurface scattering parameters (sigma_s', sigma_a of the dipole) from an image
// pair with known illumination, a patch list, or a radial profile (Mukaigawa et al. 2009).
void add_fit_profile_command(CLI::App& app);

}  // namespace skinspec::cli
