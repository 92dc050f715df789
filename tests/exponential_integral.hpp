#pragma once
// E_3(x), the exponential integral of order 3: the diffuse transmittance of a clear absorbing layer of optical depth x
// is 2 E_3(x) (Lambertian light through it).
#include <cmath>

namespace skinspec::testing {

// E_3(x) = (e^-x (1 - x) + x^2 E_1(x)) / 2 (Abramowitz & Stegun 5.1.14), E_1(x) = -Ei(-x).
inline double exponential_integral_3(double x) { return 0.5 * (std::exp(-x) * (1.0 - x) - x * x * std::expint(-x)); }

}  // namespace skinspec::testing
