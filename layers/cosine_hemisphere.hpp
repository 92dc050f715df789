#pragma once
// Cosine-weighted (Lambertian) directions about the slab normal: p(omega) = cos(theta) / pi over the
// hemisphere (Pharr, Jakob & Humphreys, pbrt-v4 Sec. A.5.3 / Malley's method, sampled directly in theta:
// cos(theta) = sqrt(u1), phi = 2 pi u2).
#include <cmath>
#include <numbers>

#include "layers/direction.hpp"

namespace skinspec {

// A direction in the hemisphere of `downward` (z > 0 when true).
inline Direction sample_cosine_hemisphere(double u1, double u2, bool downward) {
    const double cos_theta = std::sqrt(u1);
    const double sin_theta = std::sqrt(1.0 - u1);
    const double phi = 2.0 * std::numbers::pi * u2;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), downward ? cos_theta : -cos_theta};
}

// Density per steradian of a direction with |cos theta| to the normal, on its hemisphere.
inline double cosine_hemisphere_pdf(double cos_theta) { return std::abs(cos_theta) / std::numbers::pi; }

// P(cos theta <= c) = c^2: the CDF of the polar angle used in tests.
inline double cosine_hemisphere_cdf_cos(double c) { return c * c; }

}  // namespace skinspec
