#pragma once
// Statistics of run time against error (skinspec bench, docs/PERFORMANCE.md): the power law fitted in
// log-log space (a Monte Carlo walk's error falls as time^-1/2), the Pareto front over (time, error), and
// the fastest point meeting an error tolerance.
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace skinspec {

// log10 y = intercept + slope log10 x, least squares over the points with x > 0 and y > 0.
struct PowerLawFit {
    double slope = 0.0;
    double slope_stderr = 0.0;  // from the scatter about the line (0 for two points)
    double intercept = 0.0;
    std::size_t points = 0;
    // The x at which the fitted line reaches y.
    double x_at(double y) const;
};
// Nothing when fewer than two usable points or all usable x are equal.
std::optional<PowerLawFit> fit_power_law(std::span<const double> x, std::span<const double> y);

// true for the points no other point beats: none is at most as slow and at most as wrong, and better in one.
std::vector<bool> pareto_front(std::span<const double> seconds, std::span<const double> errors);

// The fastest point whose error is at most `tolerance`.
std::optional<std::size_t> fastest_within(std::span<const double> seconds, std::span<const double> errors, double tolerance);

}  // namespace skinspec
