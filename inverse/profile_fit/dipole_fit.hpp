#pragma once
// Fitting the dipole (Jensen et al. 2001 Eq. 4) to a radial profile (Mukaigawa et al. 2009 Eq. 25): minimise
// sum_i (R'_i - R(d'_i))^2 over (sigma_s', sigma_a) at a known eta. The paper's exhaustive grid (Table 1:
// sigma_s' 0.01-3.00 by 0.01, sigma_a 0-0.010 by 0.001, per mm), then a bounded local optimiser (NLopt
// BOBYQA) from the grid's best within the grid's box. With a measured total diffuse reflectance (Jensen et al. 2001
// Sec. 3), sigma_a follows from sigma_s' through the closed-form R_d(alpha'), leaving a 1-D search.
#include <optional>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace skinspec {

struct ParameterGrid {
    double first = 0.0;
    double last = 0.0;
    double step = 0.0;
};

struct DipoleFitOptions {
    double eta = 1.3;
    ParameterGrid reduced_scattering_per_mm{0.01, 3.0, 0.01};
    ParameterGrid absorption_per_mm{0.0, 0.010, 0.001};
    bool refine = true;
    std::optional<double> total_diffuse_reflectance;
};

struct DipoleFitResult {
    double reduced_scattering_per_mm = 0.0;
    double absorption_per_mm = 0.0;
    double residual = 0.0;  // Eq. 25 at the result (per mm^4)
    double grid_reduced_scattering_per_mm = 0.0;
    double grid_absorption_per_mm = 0.0;
    double grid_residual = 0.0;
    int evaluations = 0;
    // Standard errors from the residual scatter: s^2 (J^T J)^-1 with s^2 = residual / (n - p) and J the dipole's
    // derivatives at the result (Gauss-Newton; independent, equal errors assumed). NaN where the bins do not
    // determine them (no more bins than parameters, or J^T J singular).
    double reduced_scattering_stderr_per_mm = std::numeric_limits<double>::quiet_NaN();
    double absorption_stderr_per_mm = std::numeric_limits<double>::quiet_NaN();
    // The parameters that ended on an edge of the search box, e.g. "sigma_s' = 3 /mm, the search's upper bound": the
    // minimum may lie outside it (widen the grid), or the data do not constrain the parameter.
    std::vector<std::string> at_bounds;
};

// Bins with `use` = 0 are left out. InputError for sizes that differ, no usable bin, NaN values, grids with
// last < first or step <= 0, eta outside (0.2, 5), or a total reflectance the dipole cannot reach at eta.
DipoleFitResult fit_dipole(std::span<const double> distances_mm, std::span<const double> profile_per_mm2, std::span<const char> use,
                           const DipoleFitOptions& options);

// sigma_a / sigma_s' such that the dipole's closed-form total reflectance at eta equals `total` (bisection on
// the reduced albedo); InputError when `total` is outside (0, R_d(alpha' = 1)).
double absorption_ratio_for_total(double total, double eta);

}  // namespace skinspec
