#pragma once
// Registry entry "adding-doubling": deterministic radiative transfer in layered slabs (transport/adding_doubling/,
// docs/ADDING_DOUBLING.md; van de Hulst 1980, Prahl 1995) on the same volumetric description the rte walk uses.
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& adding_doubling_solver();

}  // namespace skinspec
