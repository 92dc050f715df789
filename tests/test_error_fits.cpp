#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "studies/benchmark/error_fits.hpp"

using namespace skinspec;

TEST_CASE("an exact power law is fitted exactly", "[error_fits]") {
    // y = 0.3 x^-1/2: the Monte Carlo law (error ~ 1 / sqrt(work)).
    std::vector<double> x, y;
    for (const double t : {0.001, 0.01, 0.1, 1.0, 10.0}) {
        x.push_back(t);
        y.push_back(0.3 / std::sqrt(t));
    }
    const auto fit = fit_power_law(x, y);
    REQUIRE(fit);
    CHECK(fit->slope == Approx(-0.5).margin(1e-12));
    CHECK(fit->intercept == Approx(std::log10(0.3)).margin(1e-12));
    CHECK(fit->x_at(0.003) == Approx(10000.0).epsilon(1e-9));
    CHECK(fit->points == 5);
    CHECK(fit->slope_stderr == Approx(0.0).margin(1e-12));
    // Scatter about the line: y = x^-1/2 * (1.1, 0.9, 1.1, 0.9), the textbook slope standard error.
    const std::vector<double> xs{1.0, 10.0, 100.0, 1000.0};
    std::vector<double> ys;
    for (std::size_t i = 0; i < xs.size(); ++i) ys.push_back((i % 2 ? 0.9 : 1.1) / std::sqrt(xs[i]));
    const auto noisy = fit_power_law(xs, ys);
    REQUIRE(noisy);
    double mean = 0.0, sxx = 0.0, squares = 0.0;
    for (const double v : xs) mean += std::log10(v) / 4.0;
    for (const double v : xs) sxx += (std::log10(v) - mean) * (std::log10(v) - mean);
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const double r = std::log10(ys[i]) - noisy->intercept - noisy->slope * std::log10(xs[i]);
        squares += r * r;
    }
    CHECK(noisy->slope_stderr == Approx(std::sqrt(squares / 2.0 / sxx)).epsilon(1e-9));
    // Non-positive and non-finite points are left out; one usable point is not a fit.
    CHECK(fit_power_law(std::vector<double>{1.0, 0.0, -1.0}, std::vector<double>{1.0, 2.0, 3.0}) == std::nullopt);
    CHECK(fit_power_law(std::vector<double>{2.0, 2.0}, std::vector<double>{1.0, 3.0}) == std::nullopt);
}

TEST_CASE("the Pareto front and the fastest point within a tolerance", "[error_fits]") {
    const std::vector<double> seconds{1.0, 2.0, 3.0, 0.5, 2.0};
    const std::vector<double> errors{0.10, 0.05, 0.06, 0.20, 0.05};
    const auto front = pareto_front(seconds, errors);
    CHECK(front == std::vector<bool>{true, true, false, true, true});  // the two equal points both stay
    CHECK(fastest_within(seconds, errors, 0.06) == 1u);
    CHECK(fastest_within(seconds, errors, 0.5) == 3u);
    CHECK(fastest_within(seconds, errors, 0.01) == std::nullopt);
}
