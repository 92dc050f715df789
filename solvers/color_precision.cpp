#include "solvers/color_precision.hpp"

#include <cmath>
#include <limits>

#include "spectral/color_uncertainty.hpp"

namespace skinspec {

std::function<std::vector<double>(const std::vector<Estimate>&, const std::vector<std::uint64_t>&)> color_stderr_targets(
    TristimulusWeights weights, double delta_e) {
    return [weights = std::move(weights), delta_e](const std::vector<Estimate>& estimates, const std::vector<std::uint64_t>& rays) {
        const std::size_t n = estimates.size();
        std::vector<double> values(n);
        for (std::size_t i = 0; i < n; ++i) values[i] = estimates[i].value;
        const auto a = ciede2000_sensitivities(weights, values);
        std::vector<double> v(n);
        double denominator = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            v[i] = estimates[i].stderr * estimates[i].stderr * static_cast<double>(rays[i]);
            denominator += std::sqrt(a[i] * v[i]);
        }
        std::vector<double> targets(n, std::numeric_limits<double>::infinity());
        if (denominator <= 0.0) return targets;
        for (std::size_t i = 0; i < n; ++i) {
            if (a[i] > 0.0) targets[i] = std::sqrt(std::sqrt(v[i] / a[i]) * delta_e * delta_e / denominator);
        }
        return targets;
    };
}

}  // namespace skinspec
