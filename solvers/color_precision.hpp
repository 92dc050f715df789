#pragma once
// Ray budgets driven by a colour tolerance: per-wavelength standard-error targets that bring the CIEDE2000
// uncertainty of the reflectance colour (spectral/color_uncertainty.hpp) to `delta_e` with the fewest rays.
// Neyman allocation: minimising sum N_i subject to sum a_i v_i / N_i = dE^2 gives N_i ~ sqrt(a_i v_i), i.e.
//   sigma_i^2 = sqrt(v_i / a_i) dE^2 / sum_j sqrt(a_j v_j),
// with v_i = sigma_i^2 N_i the per-ray variance estimated so far. Insensitive wavelengths (a_i = 0) get no
// target beyond their first round.
#include "transport/spectral_request.hpp"
#include "spectral/colorimetry.hpp"

namespace skinspec {

// For SpectralRequest::stderr_targets; `weights` must be built for the request's wavelengths.
std::function<std::vector<double>(const std::vector<Estimate>&, const std::vector<std::uint64_t>&)> color_stderr_targets(
    TristimulusWeights weights, double delta_e);

}  // namespace skinspec
