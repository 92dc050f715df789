#pragma once
// Registry entry "biospec-adding-doubling": the BioSpec model (the walk's per-crossing description) solved
// deterministically by adding (transport/adding_doubling/biospec_adding_doubling.hpp, docs/ADDING_DOUBLING.md).
#include "solvers/spectral_solver.hpp"

namespace skinspec {

const SpectralSolver& biospec_adding_doubling_solver();

}  // namespace skinspec
