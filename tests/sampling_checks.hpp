#pragma once
// Distribution checks shared by the sampler tests: a one-sample Kolmogorov-Smirnov statistic against an
// analytic CDF (Press et al., Numerical Recipes 3rd ed., Sec. 14.3.3).
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace skinspec::testing {

// sqrt(N) * max |F_empirical - F|; below 1.63 at the 1 % level for a correct sampler.
inline double ks_statistic(std::vector<double> samples, const std::function<double(double)>& cdf) {
    std::sort(samples.begin(), samples.end());
    const double n = static_cast<double>(samples.size());
    double d = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const double f = cdf(samples[i]);
        d = std::max({d, std::abs(f - static_cast<double>(i) / n), std::abs(static_cast<double>(i + 1) / n - f)});
    }
    return std::sqrt(n) * d;
}

inline constexpr double ks_critical_1_percent = 1.63;

}  // namespace skinspec::testing
