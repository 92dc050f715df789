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

TEST_CASE("re-weighting any number of exits and layers equals the sum in double, and the gradient comes only where asked", "[exit_paths]") {
    auto random = RandomStream::for_batch(3, 500.0, 0);
    for (const std::size_t layers : {std::size_t{1}, std::size_t{3}, std::size_t{4}, std::size_t{7}}) {
        for (const std::size_t exits : {std::size_t{5}, std::size_t{37}, std::size_t{300}, std::size_t{1000}}) {
            ExitPaths paths;
            paths.resize_layers(layers);
            std::vector<double> mu(layers), scale(layers, 1.0);
            for (std::size_t k = 0; k < layers; ++k) mu[k] = 10.0 * random.uniform();
            mu[0] = 0.0;  // a layer that adds nothing to the depth still has a gradient
            double sum = 0.0;
            std::vector<double> expected_gradient(layers, 0.0);
            for (std::size_t i = 0; i < exits; ++i) {
                std::vector<double> l(layers);
                for (auto& x : l) x = static_cast<double>(static_cast<float>(random.uniform()));
                paths.add_exit(l);
                double tau = 0.0;
                for (std::size_t k = 0; k < layers; ++k) tau += mu[k] * l[k];
                const double w = std::exp(-tau);
                sum += w;
                for (std::size_t k = 0; k < layers; ++k) expected_gradient[k] -= l[k] * w;
            }
            paths.rays = exits + 3;  // three rays that left elsewhere
            std::vector<double> gradient;
            const auto r = paths.reflectance(mu, scale, &gradient);
            INFO(layers << " layers, " << exits << " exits");
            CHECK(r.value == Approx(sum / static_cast<double>(paths.rays)).epsilon(1e-5));
            for (std::size_t k = 0; k < layers; ++k) CHECK(gradient[k] == Approx(expected_gradient[k] / static_cast<double>(paths.rays)).epsilon(1e-5));
            std::vector<bool> asked(layers, false);
            asked[layers - 1] = true;
            std::vector<double> some;
            CHECK(paths.reflectance(mu, scale, &some, asked).value == r.value);
            CHECK(some[layers - 1] == gradient[layers - 1]);
            for (std::size_t k = 0; k + 1 < layers; ++k) CHECK(some[k] == 0.0);
        }
    }
}
