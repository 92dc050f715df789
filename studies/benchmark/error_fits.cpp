#include "studies/benchmark/error_fits.hpp"

#include <cmath>

namespace skinspec {

double PowerLawFit::x_at(double y) const { return std::pow(10.0, (std::log10(y) - intercept) / slope); }

std::optional<PowerLawFit> fit_power_law(std::span<const double> x, std::span<const double> y) {
    const auto usable = [&](std::size_t i) { return x[i] > 0.0 && y[i] > 0.0 && std::isfinite(x[i]) && std::isfinite(y[i]); };
    double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
        if (!usable(i)) continue;
        const double lx = std::log10(x[i]), ly = std::log10(y[i]);
        n += 1.0;
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double denominator = n * sxx - sx * sx;
    if (n < 2.0 || !(std::abs(denominator) > 1e-12 * n * n)) return std::nullopt;
    PowerLawFit fit;
    fit.slope = (n * sxy - sx * sy) / denominator;
    fit.intercept = (sy - fit.slope * sx) / n;
    fit.points = static_cast<std::size_t>(n);
    if (n > 2.0) {
        double squares = 0.0;
        for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
            if (!usable(i)) continue;
            const double r = std::log10(y[i]) - fit.intercept - fit.slope * std::log10(x[i]);
            squares += r * r;
        }
        fit.slope_stderr = std::sqrt(squares / (n - 2.0) * n / denominator);
    }
    return fit;
}

std::vector<bool> pareto_front(std::span<const double> seconds, std::span<const double> errors) {
    std::vector<bool> front(seconds.size(), true);
    for (std::size_t i = 0; i < seconds.size(); ++i) {
        for (std::size_t j = 0; j < seconds.size() && front[i]; ++j) {
            const bool no_worse = seconds[j] <= seconds[i] && errors[j] <= errors[i];
            const bool better = seconds[j] < seconds[i] || errors[j] < errors[i];
            if (j != i && no_worse && better) front[i] = false;
        }
    }
    return front;
}

std::optional<std::size_t> fastest_within(std::span<const double> seconds, std::span<const double> errors, double tolerance) {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < seconds.size(); ++i) {
        if (errors[i] <= tolerance && (!best || seconds[i] < seconds[*best])) best = i;
    }
    return best;
}

}  // namespace skinspec
