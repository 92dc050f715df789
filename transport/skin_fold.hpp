#pragma once
// Skin-fold perturbation of the surface-reflected direction (BioSpec, Krishnaswamy & Baranoski 2004;
// docs/BIOSPEC.md "One ray", step 1): polar angle about the mirror direction
//   theta = arccos( sqrt( (sigma^2 / sqrt(sigma^4 + (1 - sigma^4) u) - 1) / (sigma^2 - 1) ) ),
// azimuth 2 pi u2, with sigma in (0, 1] the fold aspect ratio. As sigma -> 1 the formula tends to
// cos^2 theta = u (cosine-distributed); at sigma = 1 that limit is used.
#include <algorithm>
#include <cmath>

namespace skinspec {

inline double skin_fold_sample_cos(double sigma, double u) {
    const double s2 = sigma * sigma;
    if (std::abs(s2 - 1.0) < 1e-9) return std::sqrt(u);
    const double s4 = s2 * s2;
    const double cos2 = (s2 / std::sqrt(s4 + (1.0 - s4) * u) - 1.0) / (s2 - 1.0);
    return std::sqrt(std::clamp(cos2, 0.0, 1.0));
}

// P(cos theta <= c), from inverting the sampling formula: with m = c^2 (sigma^2 - 1) + 1,
// u = sigma^4 (1/m^2 - 1) / (1 - sigma^4).
inline double skin_fold_cdf_cos(double sigma, double c) {
    const double s2 = sigma * sigma;
    if (std::abs(s2 - 1.0) < 1e-9) return c * c;
    const double s4 = s2 * s2;
    const double m = c * c * (s2 - 1.0) + 1.0;
    return s4 * (1.0 / (m * m) - 1.0) / (1.0 - s4);
}

// Density of cos theta: dF/dc = -4 sigma^4 c (sigma^2 - 1) / ((1 - sigma^4) m^3).
inline double skin_fold_pdf_cos(double sigma, double c) {
    const double s2 = sigma * sigma;
    if (std::abs(s2 - 1.0) < 1e-9) return 2.0 * c;
    const double s4 = s2 * s2;
    const double m = c * c * (s2 - 1.0) + 1.0;
    return -4.0 * s4 * c * (s2 - 1.0) / ((1.0 - s4) * m * m * m);
}

// The model authors' current code (docs/BIOSPEC.md, "The model authors' current code", behaviour 5):
//   theta = arccos( sqrt( (1 - u) / (u (sigma^2 - 1) + 1) ) ).
inline double skin_fold_authors_sample_cos(double sigma, double u) {
    const double cos2 = (1.0 - u) / (u * (sigma * sigma - 1.0) + 1.0);
    return std::sqrt(std::clamp(cos2, 0.0, 1.0));
}

// P(cos theta <= c) of the authors' formula: cos^2 theta decreases in u, so with m = c^2,
// P = P(u >= (1 - m) / (m (sigma^2 - 1) + 1)) = m sigma^2 / (m (sigma^2 - 1) + 1).
inline double skin_fold_authors_cdf_cos(double sigma, double c) {
    const double m = c * c;
    return m * sigma * sigma / (m * (sigma * sigma - 1.0) + 1.0);
}

}  // namespace skinspec
