// Re-weighting recorded exits (white Monte Carlo) and thinning them by analog absorption at a floor
// (transport/biospec/exit_paths.hpp), against the analytic Laplace transform of a known path-length distribution.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "transport/biospec/exit_paths.hpp"
#include "transport/random_stream.hpp"

using namespace skinspec;

namespace {

// Every ray exits, its path in the one layer exponentially distributed with mean `mean_cm`: the mean of
// exp(-mu L) is the Laplace transform 1 / (1 + mu mean).
ExitPaths exponential_paths(std::size_t n, double mean_cm) {
    ExitPaths paths;
    paths.resize_layers(1);
    auto random = RandomStream::for_batch(7, 550.0, 0);
    for (std::size_t i = 0; i < n; ++i) paths.add_exit({-mean_cm * std::log(1.0 - random.uniform())});
    paths.rays = n;
    return paths;
}

double laplace(double mu_per_cm, double mean_cm) { return 1.0 / (1.0 + mu_per_cm * mean_cm); }

}  // namespace

TEST_CASE("thinned exits re-weight to the same expectation: the analytic Laplace transform within 4 standard errors", "[exit_paths]") {
    constexpr double mean_cm = 0.5, floor_per_cm = 2.0;
    const auto white = exponential_paths(200'000, mean_cm);
    auto thinned = white;
    thinned.thin({floor_per_cm}, 11);
    // Analog absorption at 2 /cm keeps 1 / (1 + 2 * 0.5) = half of the exits.
    CHECK(static_cast<double>(thinned.exits()) / static_cast<double>(white.exits()) == Approx(laplace(floor_per_cm, mean_cm)).margin(0.005));
    for (const double mu : {0.0, 1.0, 2.0, 5.0, 20.0}) {
        for (const auto* paths : std::array<const ExitPaths*, 2>{&white, &thinned}) {
            const auto r = paths->reflectance({mu}, {1.0});
            INFO("mu_a " << mu << " /cm, " << (paths == &white ? "white" : "thinned") << ": " << r.value << " +- " << r.stderr);
            CHECK(std::abs(r.value - laplace(mu, mean_cm)) <= 4.0 * r.stderr + 1e-12);  // white at mu 0: exactly 1
        }
    }
    // The gradient is that of the same function: d/dmu of 1 / (1 + mu mean) = -mean / (1 + mu mean)^2.
    std::vector<double> gradient;
    const auto r = thinned.reflectance({5.0}, {1.0}, &gradient);
    CHECK(gradient[0] == Approx(-mean_cm / std::pow(1.0 + 5.0 * mean_cm, 2)).epsilon(0.05));
    CHECK(r.value > 0.0);
}

TEST_CASE("thinning is reproducible for a seed and draws anew for another", "[exit_paths]") {
    auto a = exponential_paths(10'000, 0.5), b = a, c = a;
    a.thin({1.0}, 3);
    b.thin({1.0}, 3);
    c.thin({1.0}, 4);
    CHECK(a.layer_path_cm == b.layer_path_cm);
    CHECK(a.layer_path_cm != c.layer_path_cm);
}
