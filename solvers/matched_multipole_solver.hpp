#pragma once
// Registry entry "matched-multipole": the skin's totals by the exact transport of the BioSpec model
// (biospec-adding-doubling) and its radial profiles by the layered multipole, scaled per wavelength so that they
// integrate to those totals (the albedo-matching practice of production renderers; docs/DIFFUSION.md): the BioSpec
// model's colour (diffusion's own is off by CIEDE2000 5-10 on the skin presets), diffusion's shape (stated where used).
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& matched_multipole_solver();

}  // namespace skinspec
