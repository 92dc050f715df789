#pragma once
// First-order propagation of independent per-wavelength standard errors of a reflectance spectrum to the
// uncertainty of its colour as a CIEDE2000 difference: with XYZ = W r (colorimetry.hpp), Lab = Lab(XYZ)
// (CIE 015:2018 Eq. 8.1-8.3, Jacobian J analytic) and the local quadratic form of CIEDE2000,
// dE00^2(Lab, Lab + d) ~ d^T G d (G half the Hessian of dE00^2 at d = 0, by central differences),
//   E[dE00^2] = sum_i a_i sigma_i^2,  a_i = w_i^T J^T G J w_i.
#include <span>
#include <vector>

#include "spectral/colorimetry.hpp"

namespace skinspec {

// a_i: the contribution of a unit standard error at sample i to the expected squared CIEDE2000 error.
std::vector<double> ciede2000_sensitivities(const TristimulusWeights& weights, std::span<const double> samples);

// sqrt(sum_i a_i sigma_i^2): the RMS CIEDE2000 difference between the estimated and the true colour.
double ciede2000_uncertainty(const TristimulusWeights& weights, std::span<const double> samples,
                             std::span<const double> standard_errors);

}  // namespace skinspec
