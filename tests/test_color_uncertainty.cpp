#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "spectral/ciede2000.hpp"
#include "spectral/color_uncertainty.hpp"

using namespace skinspec;

TEST_CASE("propagated CIEDE2000 uncertainty matches a Monte Carlo of noisy spectra", "[color_uncertainty]") {
    // Independent check: perturb the spectrum with Gaussian noise of the stated standard errors and measure
    // the RMS CIEDE2000 difference directly.
    std::vector<double> nm, r, se;
    for (double w = 380.0; w <= 780.0; w += 10.0) {
        nm.push_back(w);
        r.push_back(0.1 + 0.35 / (1.0 + std::exp(-(w - 590.0) / 20.0)));
        se.push_back(0.002 + 0.001 * std::sin(w / 30.0));
    }
    for (const auto kind : {IlluminantKind::d65, IlluminantKind::a}) {
        const TristimulusWeights weights(nm, kind, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
        const double predicted = ciede2000_uncertainty(weights, r, se);
        const Lab truth = xyz_to_lab(weights.integrate(r), weights.white());
        std::mt19937_64 engine(42);
        std::normal_distribution<double> normal;
        double sum = 0.0;
        const int n = 20000;
        std::vector<double> noisy(r.size());
        for (int k = 0; k < n; ++k) {
            for (std::size_t i = 0; i < r.size(); ++i) noisy[i] = r[i] + se[i] * normal(engine);
            const double e = ciede2000(truth, xyz_to_lab(weights.integrate(noisy), weights.white()));
            sum += e * e;
        }
        CHECK(predicted == Approx(std::sqrt(sum / n)).epsilon(0.03));
        CHECK(predicted > 0.0);
    }
}

TEST_CASE("zero standard errors give zero colour uncertainty", "[color_uncertainty]") {
    const std::vector<double> nm{400, 550, 700}, r{0.2, 0.3, 0.5}, se{0, 0, 0};
    const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    CHECK(ciede2000_uncertainty(weights, r, se) == 0.0);
    CHECK_THROWS(ciede2000_uncertainty(weights, r, std::vector<double>{0.0}));
}
