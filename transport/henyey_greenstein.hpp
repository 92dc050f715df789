#pragma once
// Henyey-Greenstein phase function (Henyey & Greenstein 1941; Baranoski et al. 2005 Eq. 1):
//   p(theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)) per steradian,
// sampled by Baranoski et al. 2005 Eq. 5: cos theta = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g), and 1 - 2u at g = 0.
#include <algorithm>
#include <cmath>
#include <numbers>

namespace skinspec {

inline double hg_sample_cos(double g, double u) {
    if (std::abs(g) < 1e-6) return 1.0 - 2.0 * u;
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

inline double hg_eval(double g, double cos_theta) {
    const double denom = 1.0 + g * g - 2.0 * g * cos_theta;
    return (1.0 - g * g) / (4.0 * std::numbers::pi * denom * std::sqrt(denom));
}

// Density of cos theta (2 pi times the per-steradian value).
inline double hg_pdf_cos(double g, double cos_theta) { return 2.0 * std::numbers::pi * hg_eval(g, cos_theta); }

// P(cos <= c) in closed form: (1 - g^2)/(2g) [1/sqrt(1 + g^2 - 2gc) - 1/(1 + g)].
inline double hg_cdf_cos(double g, double c) {
    if (std::abs(g) < 1e-6) return 0.5 * (c + 1.0);
    return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * c) - 1.0 / (1.0 + g));
}

}  // namespace skinspec
