#include <catch2/catch.hpp>

#include "transport/random_stream.hpp"
#include "transport/rayleigh_phase.hpp"
#include "sampling_checks.hpp"

using namespace skinspec;

TEST_CASE("Rayleigh sampling inverts its CDF", "[rayleigh_phase]") {
    auto random = RandomStream::for_batch(11, 450.0, 0);
    std::vector<double> mu;
    for (int i = 0; i < 200000; ++i) mu.push_back(rayleigh_sample_cos(random.uniform()));
    CHECK(testing::ks_statistic(mu, rayleigh_cdf_cos) < testing::ks_critical_1_percent);
    // Exact inversion at the ends and the middle.
    CHECK(rayleigh_sample_cos(0.0) == Approx(-1.0).margin(1e-12));
    CHECK(rayleigh_sample_cos(0.5) == Approx(0.0).margin(1e-12));
    CHECK(rayleigh_sample_cos(1.0) == Approx(1.0).margin(1e-12));
    // <cos^2> = 2/5 for Rayleigh (Chandrasekhar 1960).
    double m2 = 0.0;
    for (const double m : mu) m2 += m * m;
    CHECK(m2 / static_cast<double>(mu.size()) == Approx(0.4).margin(0.003));
}

TEST_CASE("Rayleigh pdf and eval are normalised and consistent", "[rayleigh_phase]") {
    double integral = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) integral += rayleigh_pdf_cos(-1.0 + (i + 0.5) * 2.0 / n) * 2.0 / n;
    CHECK(integral == Approx(1.0).epsilon(1e-6));
    CHECK(rayleigh_eval(0.3) * 2.0 * std::numbers::pi == Approx(rayleigh_pdf_cos(0.3)));
}
