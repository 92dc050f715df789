#pragma once
// Cosine-weighted (Lambertian) directions about the slab normal: p(omega) = cos(theta) / pi over the
// hemisphere (Pharr, Jakob & Humphreys, pbrt-v4 Sec. A.5.3 / Malley's method, sampled directly in theta:
// cos(theta) = sqrt(u), phi uniform).
#include <cmath>
#include <numbers>

#include "transport/direction.hpp"

namespace skinspec {

// A direction in the hemisphere of `downward` (z > 0 when true), from u uniform in [0, 1) and a uniform azimuth.
inline Direction sample_cosine_hemisphere(double u, Azimuth azimuth, bool downward) {
    const double cos_theta = std::sqrt(u);
    const double sin_theta = std::sqrt(1.0 - u);
    return {sin_theta * azimuth.cos_phi, sin_theta * azimuth.sin_phi, downward ? cos_theta : -cos_theta};
}

// Density per steradian of a direction with |cos theta| to the normal, on its hemisphere.
inline double cosine_hemisphere_pdf(double cos_theta) { return std::abs(cos_theta) / std::numbers::pi; }

// P(cos theta <= c) = c^2: the CDF of the polar angle used in tests.
inline double cosine_hemisphere_cdf_cos(double c) { return c * c; }

}  // namespace skinspec
