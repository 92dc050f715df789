#pragma once
// Registry entry "rte": the volumetric (MCML-class) walk (transport/rte/, docs/RTE.md; Wang, Jacques & Zheng
// 1995) behind the solver interface; every layer needs volumetric_* scattering.
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& volumetric_walk_solver();

}  // namespace skinspec
