#pragma once
// Registry entries "multipole" (layered diffusion; Donner & Jensen 2005) and "dipole" (semi-infinite
// diffusion; Jensen et al. 2001) behind the solver interface (transport/diffusion/, docs/DIFFUSION.md).
// Deterministic: no standard errors; R and T, radial profiles; layered materials need reduced scattering.
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& multipole_solver();
const SpectralSolver& dipole_solver();

}  // namespace skinspec
