#pragma once
// Registry entry "biospec": the BioSpec walk (transport/biospec/, docs/BIOSPEC.md; Krishnaswamy & Baranoski
// 2004) behind the solver interface.
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& biospec_walk_solver();

}  // namespace skinspec
