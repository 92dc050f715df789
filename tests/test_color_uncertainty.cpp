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

TEST_CASE("propagated L*, a*, b* uncertainties match the spread of noisy spectra, with and without a common error", "[color_uncertainty]") {
    // Brute force: many spectra with independent Gaussian noise of the standard errors (and, second, an error
    // common to every sample, as a deterministic solver's stated error is taken); the standard deviations of
    // their L*, a*, b* and the RMS CIEDE2000 from the truth must match the linear propagation within 10 %.
    std::vector<double> nm, r, se;
    for (double w = 400.0; w <= 700.0; w += 10.0) {
        nm.push_back(w);
        r.push_back(0.08 + 0.3 / (1.0 + std::exp(-(w - 580.0) / 25.0)));
        se.push_back(0.003 + 0.002 * std::cos(w / 40.0));
    }
    const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    const Lab truth = xyz_to_lab(weights.integrate(r), weights.white());
    for (const double stated : {0.0, 0.004}) {
        INFO("stated error " << stated);
        const auto u = color_uncertainty(weights, r, se, stated);
        std::mt19937_64 engine(7);
        std::normal_distribution<double> normal;
        const int n = 20000;
        std::vector<double> noisy(r.size());
        double sl = 0, sa = 0, sb = 0, sl2 = 0, sa2 = 0, sb2 = 0, se2 = 0;
        for (int k = 0; k < n; ++k) {
            const double common = stated * normal(engine);
            for (std::size_t i = 0; i < r.size(); ++i) noisy[i] = r[i] + se[i] * normal(engine) + common;
            const Lab lab = xyz_to_lab(weights.integrate(noisy), weights.white());
            sl += lab.L, sa += lab.a, sb += lab.b;
            sl2 += lab.L * lab.L, sa2 += lab.a * lab.a, sb2 += lab.b * lab.b;
            const double e = ciede2000(truth, lab);
            se2 += e * e;
        }
        const auto sd = [&](double s, double s2) { return std::sqrt(s2 / n - (s / n) * (s / n)); };
        CHECK(u.lab.L == Approx(sd(sl, sl2)).epsilon(0.1));
        CHECK(u.lab.a == Approx(sd(sa, sa2)).epsilon(0.1));
        CHECK(u.lab.b == Approx(sd(sb, sb2)).epsilon(0.1));
        CHECK(u.delta_e2000 == Approx(std::sqrt(se2 / n)).epsilon(0.1));
    }
    CHECK_THROWS_WITH(color_uncertainty(weights, r, se, -1.0), Catch::Contains("stated error"));
    CHECK_THROWS_WITH(color_uncertainty(weights, r, std::vector<double>(r.size(), std::nan(""))), Catch::Contains("standard error"));
}

TEST_CASE("zero standard errors give zero colour uncertainty", "[color_uncertainty]") {
    const std::vector<double> nm{400, 550, 700}, r{0.2, 0.3, 0.5}, se{0, 0, 0};
    const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    CHECK(ciede2000_uncertainty(weights, r, se) == 0.0);
    CHECK_THROWS(ciede2000_uncertainty(weights, r, std::vector<double>{0.0}));
}

TEST_CASE("a common error on a grey spectrum moves only L*: finite a* and b* uncertainties of 0, L*'s by the CIE slope", "[color_uncertainty]") {
    // A grey (constant) spectrum stays grey when shifted by a common error: a* = b* = 0 exactly, so their variance is 0
    // (it rounded below 0: b* uncertainty NaN in `export lut`'s spectra of dark skin). L* = 116 f(Y) - 16 with
    // Y = R for a grey of reflectance R under any illuminant; below (6/29)^3 L* = (29/3)^3 Y (CIE 015:2018 Eq. 8.1).
    std::vector<double> nm;
    for (double w = 380.0; w <= 780.0; w += 5.0) nm.push_back(w);
    const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    const std::vector<double> se(nm.size(), 0.0);
    for (const double grey : {0.002, 0.005, 0.05, 0.3}) {
        INFO("R = " << grey);
        const std::vector<double> r(nm.size(), grey);
        const double stated = 1e-4;
        const auto u = color_uncertainty(weights, r, se, stated);
        CHECK(std::isfinite(u.lab.a));
        CHECK(std::isfinite(u.lab.b));
        CHECK(u.lab.a < 1e-6);
        CHECK(u.lab.b < 1e-6);
        const double slope = grey > std::pow(6.0 / 29.0, 3) ? 116.0 / 3.0 * std::pow(grey, -2.0 / 3.0) : std::pow(29.0 / 3.0, 3);
        CHECK(u.lab.L == Approx(slope * stated).epsilon(1e-3));
    }
}
