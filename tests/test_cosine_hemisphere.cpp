#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "transport/cosine_hemisphere.hpp"
#include "transport/random_stream.hpp"
#include "sampling_checks.hpp"

using namespace skinspec;

TEST_CASE("cosine-weighted directions follow P(cos <= c) = c^2", "[cosine_hemisphere]") {
    auto random = RandomStream::for_batch(7, 500.0, 0);
    std::vector<double> cosines;
    for (int i = 0; i < 100000; ++i) {
        const double u = random.uniform();
        const auto d = sample_cosine_hemisphere(u, sample_azimuth(random), i % 2 == 0);
        CHECK(std::abs(glm::length(d) - 1.0) < 1e-12);
        CHECK((d.z >= 0.0) == (i % 2 == 0));
        cosines.push_back(std::abs(d.z));
    }
    // Against the formula itself (a cosine-weighted pdf 2 mu in mu = cos theta integrates to mu^2), not the library's CDF.
    CHECK(testing::ks_statistic(cosines, [](double mu) { return mu * mu; }) < testing::ks_critical_1_percent);
    CHECK(cosine_hemisphere_cdf_cos(0.5) == Approx(0.25));
    CHECK(cosine_hemisphere_pdf(1.0) == Approx(1.0 / std::numbers::pi));
}

TEST_CASE("uniform azimuths have uniform angle", "[cosine_hemisphere]") {
    auto random = RandomStream::for_batch(3, 600.0, 1);
    std::vector<double> phi;
    for (int i = 0; i < 100000; ++i) {
        const auto a = sample_azimuth(random);
        CHECK(a.cos_phi * a.cos_phi + a.sin_phi * a.sin_phi == Approx(1.0).epsilon(1e-12));
        phi.push_back(std::atan2(a.sin_phi, a.cos_phi));
    }
    const auto cdf = [](double x) { return (x + std::numbers::pi) / (2.0 * std::numbers::pi); };
    CHECK(testing::ks_statistic(phi, cdf) < testing::ks_critical_1_percent);
}
