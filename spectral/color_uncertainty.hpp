#pragma once
// First-order propagation of independent per-wavelength standard errors of a reflectance spectrum to the
// uncertainty of its colour as a CIEDE2000 difference: with XYZ = W r (colorimetry.hpp), Lab = Lab(XYZ)
// (CIE 015:2018 Eq. 8.1-8.3, Jacobian J analytic) and the local quadratic form of CIEDE2000,
// dE00^2(Lab, Lab + d) ~ d^T G d (G half the Hessian of dE00^2 at d = 0, by central differences),
//   E[dE00^2] = sum_i a_i sigma_i^2,  a_i = w_i^T J^T G J w_i.
//
// The same linear propagation gives the standard uncertainties of XYZ, L*, a*, b* (and, through a caller's
// Jacobian, of any RGB): Cov(XYZ) = sum_i sigma_i^2 w_i w_i^T + s^2 (sum_i w_i)(sum_i w_i)^T, Cov(Lab) = J Cov(XYZ) J^T,
// where sigma_i are independent per-sample standard errors (Monte Carlo) and s a deterministic solver's stated
// error in R, taken as common to every sample (fully correlated: the larger colour error of the two extremes).
#include <array>
#include <span>
#include <string_view>
#include <vector>

#include "spectral/colorimetry.hpp"

namespace skinspec {

using Matrix3 = std::array<std::array<double, 3>, 3>;

struct ColorUncertainty {
    Matrix3 xyz_covariance{};
    Lab lab;                   // standard uncertainties of L*, a*, b*
    double delta_e2000 = 0.0;  // RMS CIEDE2000 difference between the estimated and the true colour
};

// InputError unless there is one standard error per sample, each finite and >= 0, and `stated_error` is finite and >= 0.
ColorUncertainty color_uncertainty(const TristimulusWeights& weights, std::span<const double> samples,
                                   std::span<const double> standard_errors, double stated_error = 0.0);

// Standard uncertainties of `space`'s values (a colour space of the shipped OCIO config, e.g. encoded "sRGB") of
// the colour `xyz` whose XYZ covariance is `xyz_covariance`: J Cov(XYZ) J^T, J by central differences of the same
// transform (step 1e-3 in XYZ, where OCIO's float32 rounding stays ~1e-4 of the derivative).
std::array<double, 3> rgb_uncertainty(const XYZ& xyz, const XYZ& white, const Matrix3& xyz_covariance, std::string_view space);

// a_i: the contribution of a unit standard error at sample i to the expected squared CIEDE2000 error.
std::vector<double> ciede2000_sensitivities(const TristimulusWeights& weights, std::span<const double> samples);

// sqrt(sum_i a_i sigma_i^2): the RMS CIEDE2000 difference between the estimated and the true colour
// (color_uncertainty's delta_e2000 without a stated error).
double ciede2000_uncertainty(const TristimulusWeights& weights, std::span<const double> samples,
                             std::span<const double> standard_errors);

}  // namespace skinspec
