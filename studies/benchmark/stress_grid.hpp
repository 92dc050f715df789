#pragma once
// The stability suite (docs/STABILITY.md): every solver over a grid of extremes - anisotropy, albedo,
// thickness, refractive index, incidence, wavelengths at the tables' edges, concentrations 0 and maximal,
// large ray budgets in tiny layers. Each case must give finite values in [0, 1] that conserve energy, within a
// bounded run time; where physics orders two cases (more absorption, less reflection; thicker, less
// transmission) the order is checked. A case that meets a documented limit (an InputError naming the range,
// rays stopped at the event limit, diffusion's trust warnings) passes and reports the limit.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "transport/spectral_request.hpp"

namespace skinspec {

struct StressOutcome {
    std::string solver;   // rte, biospec, dipole, multipole, diffusion-stack, adding-doubling, adding-doubling-stack
    std::string name;     // the case's parameters
    double seconds = 0.0;
    bool passed = true;
    std::string failure;  // what failed
    std::string limit;    // the documented limit the case met, if any
};

struct StressOptions {
    bool full = false;                  // the full grid (minutes); the short one runs in ctest
    std::uint64_t seed = 1;
    double max_seconds_per_case = 60.0;  // the run-time bound
    std::function<void(const StressOutcome&)> on_case;
    const CancelFlag* cancel = nullptr;
};

struct StressReport {
    std::vector<StressOutcome> outcomes;
    bool partial = false;  // stopped by the cancel flag
    std::size_t failures() const;
    std::size_t limits() const;
};

StressReport run_stress_grid(const StressOptions& options);

}  // namespace skinspec
