#pragma once
// Diffusion profiles as sums of Gaussians, the form real-time and offline skin renderers take them in
// (d'Eon, Luebke & Enderton 2007, "Efficient rendering of human skin", Sec. 4; d'Eon & Luebke 2007, GPU Gems 3
// ch. 14, Eq. 14-3 and Table 14-1, six Gaussians for skin):
//   R_c(r) ~ sum_i w_ci G(v_i, r),   G(v, r) = exp(-r^2 / (2 v)) / (2 pi v),
// one set of variances v_i (mm^2) shared by every channel c (colour band or wavelength), weights w_ci >= 0.
// Each G integrates to 1 over the plane, so sum_i w_ci is the fit's total diffuse reflectance of channel c.
// The fit minimises, as d'Eon et al. do, the error integrated over the plane (weight r dr), relative per channel:
//   E = sum_c [ int (R_c - fit_c)^2 r dr / int R_c^2 r dr + (sum_i w_ci / T_c - 1)^2 ],
// the second term holding the fit's total to the channel's total diffuse reflectance T_c over the whole plane
// (what a renderer's albedo must keep) when it is given;
// for given variances the weights are a non-negative least-squares problem per channel (Lawson & Hanson 1974,
// "Solving Least Squares Problems", ch. 23), the log-variances are searched by BOBYQA (NLopt).
#include <cstddef>
#include <vector>

namespace skinspec {

// G(v, r) in 1/mm^2 for v in mm^2 and r in mm.
double gaussian_2d(double variance_mm2, double r_mm);

struct GaussianSumRequest {
    std::vector<double> radii_mm;                      // increasing, from >= 0, at least 8
    std::vector<std::vector<double>> profiles_per_mm2;  // per channel, one value per radius, finite
    std::size_t gaussians = 6;                          // [1, 12]
    std::vector<double> total_reflectance;              // T_c per channel (> 0), or empty: the profile alone
    // Given (`gaussians` of them, > 0, increasing): kept, and only the weights are fitted (the non-negative least
    // squares alone): profiles that share another fit's variances, as the members of a pigmentation grid do.
    std::vector<double> variances_mm2;
};

struct GaussianSumFit {
    std::vector<double> variances_mm2;           // increasing
    std::vector<std::vector<double>> weights;    // [channel][gaussian], >= 0
    std::vector<double> relative_l2_error;       // per channel: sqrt(int (R - fit)^2 r dr / int R^2 r dr)
    std::vector<double> fitted_total;            // per channel: sum_i w_ci
    std::vector<double> profile_total;           // per channel: 2 pi int R r dr over the given radii (trapezoid)
    std::size_t evaluations = 0;
};

// InputError for a Gaussian count outside [1, 12].
void check_gaussian_count(std::size_t gaussians);

// Solves min |A x - b|^2 subject to x >= 0 (Lawson-Hanson active set); A is rows x cols, row-major.
std::vector<double> non_negative_least_squares(const std::vector<double>& a, std::size_t rows, std::size_t cols, const std::vector<double>& b);

// InputError for too few radii, radii not increasing or negative, a profile of the wrong length or with a
// non-finite value, an all-zero profile, or a Gaussian count outside [1, 12].
GaussianSumFit fit_gaussian_sum(const GaussianSumRequest& request);

}  // namespace skinspec
