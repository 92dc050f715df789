#pragma once
// Legendre moments chi_l = (1/2) int_{-1}^{1} p(mu) P_l(mu) dmu of a volumetric phase function normalised to
// chi_0 = 1 (p the density of the deflection cosine), for the adding-doubling solver: HG chi_l = g^l
// (Henyey & Greenstein 1941), two-term HG the weighted sum, isotropic chi_l = 0 (l > 0), Rayleigh chi_2 = 1/10
// (Chandrasekhar 1960, Eq. I.(26)), tabulated: the mean of P_l over the inverse-CDF table's equally probable
// entries (the same distribution the walk samples).
#include <cstddef>
#include <vector>

#include "transport/phase_function.hpp"

namespace skinspec {

// chi_0 ... chi_count-1.
std::vector<double> legendre_moments(const PhaseFunction& phase, std::size_t count);

// P_0(x) ... P_count-1(x) by Bonnet's recurrence.
std::vector<double> legendre_polynomials(double x, std::size_t count);

}  // namespace skinspec
