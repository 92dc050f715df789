#include <catch2/catch.hpp>

#include "transport/henyey_greenstein.hpp"
#include "transport/random_stream.hpp"
#include "sampling_checks.hpp"

using namespace skinspec;

TEST_CASE("HG sampling (Baranoski et al. 2005 Eq. 5) follows the HG CDF and has mean cosine g", "[henyey_greenstein]") {
    for (const double g : {-0.5, 0.0, 0.3, 0.821, 0.943}) {
        INFO("g = " << g);
        auto random = RandomStream::for_batch(5, 546.0, static_cast<std::uint64_t>(g * 1000 + 1000));
        std::vector<double> c;
        double mean = 0.0;
        for (int i = 0; i < 100000; ++i) {
            c.push_back(hg_sample_cos(g, random.uniform()));
            mean += c.back();
        }
        CHECK(testing::ks_statistic(c, [g](double x) { return hg_cdf_cos(g, x); }) < testing::ks_critical_1_percent);
        CHECK(mean / 1e5 == Approx(g).margin(0.01));
        CHECK(hg_cdf_cos(g, 1.0) == Approx(1.0).epsilon(1e-12));
        CHECK(hg_cdf_cos(g, -1.0) == Approx(0.0).margin(1e-12));
    }
    CHECK(hg_pdf_cos(0.0, 0.2) == Approx(0.5));
}
