#pragma once
// Fitting Henyey-Greenstein to the measured forward-scattering profiles (Baranoski, Krishnaswamy & Kimmel
// 2005, Sec. 4, Eq. 6-9): bin fractions of the measured data and of HG over the 13 goniometer
// bins [0, 2.5], (2.5, 7.5], ..., (57.5, 62.5] deg, both normalised to the light within 62.5 deg, and the
// g minimising their RMS difference by Nelder-Mead over [-1, 1] (NLopt's LN_NELDERMEAD).
#include <span>
#include <vector>

namespace skinspec {

// Eq. 6: F_0 = C(2.5), F_i = C(theta_i) - C(theta_i-1) from cumulative fractions at 0, 2.5, ..., 62.5 deg.
std::vector<double> measured_bin_fractions(std::span<const double> cumulative_fraction);
// Eq. 7-8: the same bins for HG with asymmetry g, C_g,i = P(theta < theta_i) / P(theta < 62.5).
std::vector<double> hg_bin_fractions(double g, std::span<const double> bin_edges_deg);
// Eq. 9.
double rms_error(std::span<const double> measured, std::span<const double> model);

struct HgFit {
    double g = 0.0;
    double rms = 0.0;
    int evaluations = 0;
};
// Nelder-Mead from g = 0.5 to |dg| < 1e-9.
HgFit fit_hg_rms(std::span<const double> cumulative_fraction, std::span<const double> bin_edges_deg);

}  // namespace skinspec
