#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "inverse/gaussian_sum/gaussian_sum_fit.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

// d'Eon & Luebke 2007 (GPU Gems 3 ch. 14, Table 14-1): the six variances (mm^2) and red, green, blue weights of
// their sum-of-Gaussians skin profile (three-layer model of Donner & Jensen 2005).
const std::vector<double> deon_variances{0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
const std::vector<std::vector<double>> deon_weights{{0.233, 0.100, 0.118, 0.113, 0.358, 0.078},
                                                    {0.455, 0.336, 0.198, 0.007, 0.004, 0.0},
                                                    {0.649, 0.344, 0.0, 0.007, 0.0, 0.0}};

// Table 14-1's profile of weights `w` at the radii.
std::vector<double> deon_profile(const std::vector<double>& w, const std::vector<double>& radii_mm) {
    std::vector<double> p;
    for (const double r : radii_mm) {
        double v = 0.0;
        for (std::size_t i = 0; i < 6; ++i) v += w[i] * gaussian_2d(deon_variances[i], r);
        p.push_back(v);
    }
    return p;
}

std::vector<double> radii(double last, double step) {
    std::vector<double> r;
    for (int i = 0; i * step <= last + 1e-12; ++i) r.push_back(i * step);
    return r;
}

}  // namespace

TEST_CASE("each Gaussian integrates to one over the plane", "[gaussian_sum_fit]") {
    for (const double v : {0.0064, 0.5, 7.41}) {
        double sum = 0.0;
        const double h = std::sqrt(v) / 200.0;
        for (double r = 0.5 * h; r < 40.0 * std::sqrt(v); r += h) sum += 2.0 * std::numbers::pi * r * gaussian_2d(v, r) * h;
        CHECK(sum == Approx(1.0).epsilon(1e-5));  // midpoint rule, h = sigma / 200
    }
}

TEST_CASE("non-negative least squares: interior and active-constraint solutions", "[gaussian_sum_fit]") {
    // Unconstrained minimum x = (1, 2) is feasible: NNLS returns it.
    const std::vector<double> a{1, 0, 0, 1, 1, 1};
    const auto x = non_negative_least_squares(a, 3, 2, {1, 2, 3});
    CHECK(x[0] == Approx(1.0).margin(1e-12));
    CHECK(x[1] == Approx(2.0).margin(1e-12));
    // Unconstrained minimum (-1, 3) is not: the constrained one is x0 = 0, x1 = argmin (x1-b1)^2 + (x1-b2)^2 on b = (-1, 3, 2)
    // -> rows 2 and 3 give x1 = (3 + 2) / 2.
    const auto y = non_negative_least_squares(a, 3, 2, {-1, 3, 2});
    CHECK(y[0] == 0.0);
    CHECK(y[1] == Approx(2.5).margin(1e-12));
}

TEST_CASE("a profile that is a sum of Gaussians is fitted exactly, variances and weights recovered", "[gaussian_sum_fit]") {
    GaussianSumRequest request;
    request.radii_mm = radii(10.0, 0.01);
    request.gaussians = 6;
    for (const auto& w : deon_weights) {
        request.profiles_per_mm2.push_back(deon_profile(w, request.radii_mm));
        double total = 0.0;
        for (const double wi : w) total += wi;
        request.total_reflectance.push_back(total);  // the whole plane's, as a renderer's albedo
    }
    const auto fit = fit_gaussian_sum(request);
    for (std::size_t c = 0; c < 3; ++c) {
        CHECK(fit.relative_l2_error[c] < 2e-3);
        double total = 0.0;
        for (const double w : deon_weights[c]) total += w;
        CHECK(fit.fitted_total[c] == Approx(total).epsilon(1e-3));
        for (const double w : fit.weights[c]) CHECK(w >= 0.0);
    }
    REQUIRE(fit.variances_mm2.size() == 6);
    for (std::size_t i = 1; i < 6; ++i) CHECK(fit.variances_mm2[i] >= fit.variances_mm2[i - 1]);
}

TEST_CASE("given variances: only the weights are fitted, d'Eon's weights recovered for d'Eon's variances", "[gaussian_sum_fit]") {
    // Table 14-1's profile with its own variances given: the non-negative least squares alone returns its weights.
    GaussianSumRequest request;
    request.radii_mm = radii(10.0, 0.01);
    request.gaussians = 6;
    request.variances_mm2 = deon_variances;
    for (const auto& w : deon_weights) {
        request.profiles_per_mm2.push_back(deon_profile(w, request.radii_mm));
    }
    const auto fit = fit_gaussian_sum(request);
    CHECK(fit.variances_mm2 == deon_variances);
    CHECK(fit.evaluations == 0);
    for (std::size_t c = 0; c < 3; ++c) {
        CHECK(fit.relative_l2_error[c] < 1e-9);
        for (std::size_t i = 0; i < 6; ++i) CHECK(fit.weights[c][i] == Approx(deon_weights[c][i]).margin(1e-9));
    }
    request.variances_mm2 = {0.1, 0.05, 1.0, 2.0, 3.0, 4.0};
    CHECK_THROWS_WITH(fit_gaussian_sum(request), Catch::Contains("given variance 0.05 mm^2 is not positive, finite and above the one before"));
    request.variances_mm2 = {0.1, 1.0};
    CHECK_THROWS_WITH(fit_gaussian_sum(request), Catch::Contains("2 variances given for 6 Gaussians"));
}

TEST_CASE("the total-reflectance term holds the fit's albedo to the given total", "[gaussian_sum_fit]") {
    // A profile whose tail the radii cut (variance 30 mm^2 beyond 10 mm): unconstrained, the fit loses the tail's
    // reflectance; with the total given it keeps it.
    GaussianSumRequest request;
    request.radii_mm = radii(10.0, 0.05);
    request.gaussians = 3;
    std::vector<double> p;
    for (const double r : request.radii_mm) p.push_back(0.3 * gaussian_2d(0.05, r) + 0.2 * gaussian_2d(30.0, r));
    request.profiles_per_mm2 = {p};
    request.total_reflectance = {0.5};
    const auto fit = fit_gaussian_sum(request);
    CHECK(fit.fitted_total[0] == Approx(0.5).epsilon(1e-3));
    CHECK(fit.profile_total[0] < 0.5);  // the 0-10 mm range holds less than the whole plane
}

TEST_CASE("bad Gaussian-fit requests are input errors", "[gaussian_sum_fit]") {
    GaussianSumRequest request;
    request.radii_mm = radii(1.0, 0.1);
    request.profiles_per_mm2 = {std::vector<double>(request.radii_mm.size(), 1.0)};
    request.gaussians = 0;
    CHECK_THROWS_WITH(fit_gaussian_sum(request), Catch::Contains("--gaussians 0 is outside [1, 12]"));
    CHECK_THROWS_WITH(check_gaussian_count(13), Catch::Contains("--gaussians 13 is outside [1, 12]"));
    request.gaussians = 2;
    auto few = request;
    few.radii_mm = {0, 1, 2};
    few.profiles_per_mm2 = {{1, 1, 1}};
    CHECK_THROWS_WITH(fit_gaussian_sum(few), Catch::Contains("too few"));
    auto nan = request;
    nan.profiles_per_mm2[0][3] = NAN;
    CHECK_THROWS_WITH(fit_gaussian_sum(nan), Catch::Contains("profile 1 at 0.3"));
    auto zero = request;
    zero.profiles_per_mm2[0].assign(request.radii_mm.size(), 0.0);
    CHECK_THROWS_WITH(fit_gaussian_sum(zero), Catch::Contains("zero everywhere"));
    auto length = request;
    length.profiles_per_mm2[0].pop_back();
    CHECK_THROWS_WITH(fit_gaussian_sum(length), Catch::Contains("has 10 values for 11 radii"));
    auto order = request;
    order.radii_mm[4] = order.radii_mm[3];
    CHECK_THROWS_WITH(fit_gaussian_sum(order), Catch::Contains("does not increase"));
    auto total = request;
    total.total_reflectance = {-0.1};
    CHECK_THROWS_WITH(fit_gaussian_sum(total), Catch::Contains("= -0.1 is outside (0, inf)"));
}
