#include <catch2/catch.hpp>

#include <cmath>

#include "solvers/color_precision.hpp"
#include "spectral/color_uncertainty.hpp"

using namespace skinspec;

TEST_CASE("colour-driven targets meet the tolerance exactly and favour sensitive wavelengths", "[color_precision]") {
    std::vector<double> nm;
    std::vector<Estimate> estimates;
    std::vector<std::uint64_t> rays;
    for (double w = 380.0; w <= 780.0; w += 5.0) {
        nm.push_back(w);
        estimates.push_back({0.1 + 0.3 * (w - 380.0) / 400.0, 0.01});
        rays.push_back(1000);
    }
    const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    const auto targets = color_stderr_targets(weights, 0.3)(estimates, rays);
    std::vector<double> values;
    for (const auto& e : estimates) values.push_back(e.value);
    // Plugging the targets into the propagation gives the tolerance (Neyman allocation uses it all).
    CHECK(ciede2000_uncertainty(weights, values, targets) == Approx(0.3).epsilon(1e-9));
    // 555 nm matters more than 400 nm: a tighter target there.
    const auto at = [&](double w) { return targets[static_cast<std::size_t>((w - 380.0) / 5.0)]; };
    CHECK(at(555.0) < at(400.0));
    // Wavelengths the eye does not see (beyond the CMFs' reach) are insensitive: no target.
    CHECK(at(780.0) > 10.0 * at(555.0));
}
