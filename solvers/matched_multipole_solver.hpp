#pragma once
// Registry entry "matched-multipole": the skin's totals by the exact transport of the BioSpec model
// (biospec-adding-doubling) and its radial profiles by the layered multipole, scaled per wavelength so that they
// integrate to those totals (the albedo-matching practice of production renderers; docs/DIFFUSION.md). The default
// for layered materials wherever profiles are needed (swatch --lit, profile, export profile): its colour is the
// BioSpec model's, not diffusion's (which is off by CIEDE2000 5-10 on the skin presets).
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& matched_multipole_solver();

// The solver a command that needs radial profiles uses when none is named: matched-multipole for layered materials,
// the multipole for homogeneous band materials (no BioSpec description to match).
const SpectralSolver& default_profile_solver(const Material& material);

}  // namespace skinspec
