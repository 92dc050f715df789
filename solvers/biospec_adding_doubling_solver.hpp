#pragma once
// Registry entry "biospec-adding-doubling": the BioSpec model (the walk's per-crossing description) solved
// deterministically by adding (transport/adding_doubling/biospec_adding_doubling.hpp, docs/ADDING_DOUBLING.md).
#include "solvers/spectral_solver.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"

namespace skinspec {

const SpectralSolver& biospec_adding_doubling_solver();

// What biospec-adding-doubling takes from a request's switches (its capabilities' channels, fold-into-skin and
// thin-layer-phase); the quadrature is `default_channels` unless --channels is given.
BiospecAdOptions biospec_ad_options(const SolverSwitches& switches, std::size_t default_channels);

}  // namespace skinspec
