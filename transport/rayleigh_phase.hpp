#pragma once
// Rayleigh phase function p(cos a) = 3/8 (1 + cos^2 a) per unit cos a, i.e. 3/(16 pi) (1 + cos^2 a) per
// steradian (Chandrasekhar 1960, Radiative Transfer, Eq. I.(26)). Sampled by inverting its CDF exactly:
// F(mu) = (mu^3 + 3 mu + 4) / 8 = u, a depressed cubic solved by Cardano's formula.
#include <cmath>
#include <numbers>

namespace skinspec {

inline double rayleigh_sample_cos(double u) {
    const double q = 4.0 * u - 2.0;  // mu^3 + 3 mu - 2 q = 0
    // Cardano: mu = cbrt(q + sqrt(q^2 + 1)) + cbrt(q - sqrt(q^2 + 1)); the two cube roots multiply to -1.
    const double a = std::cbrt(q + std::sqrt(q * q + 1.0));
    return a - 1.0 / a;
}

inline double rayleigh_pdf_cos(double mu) { return 0.375 * (1.0 + mu * mu); }
inline double rayleigh_eval(double mu) { return 3.0 / (16.0 * std::numbers::pi) * (1.0 + mu * mu); }
inline double rayleigh_cdf_cos(double mu) { return (mu * mu * mu + 3.0 * mu + 4.0) / 8.0; }

}  // namespace skinspec
