#include <catch2/catch.hpp>

#include "transport/random_stream.hpp"
#include "transport/two_term_hg.hpp"
#include "sampling_checks.hpp"

using namespace skinspec;

TEST_CASE("two-term HG sampling follows its CDF (Baranoski et al. 2005 Eq. 2)", "[two_term_hg]") {
    auto random = RandomStream::for_batch(21, 500.0, 0);
    std::vector<double> c;
    double mean = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const double u1 = random.uniform(), u2 = random.uniform();
        c.push_back(two_term_hg_sample_cos(0.5, -0.5, 0.7, u1, u2));
        mean += c.back() / 1e5;
    }
    CHECK(testing::ks_statistic(c, [](double x) { return two_term_hg_cdf_cos(0.5, -0.5, 0.7, x); }) < testing::ks_critical_1_percent);
    CHECK(mean == Approx(0.7 * 0.5 - 0.3 * 0.5).margin(0.01));  // <cos> = u g1 + (1 - u) g2
    CHECK(two_term_hg_pdf_cos(0.5, -0.5, 0.7, 0.3) == Approx(0.7 * hg_pdf_cos(0.5, 0.3) + 0.3 * hg_pdf_cos(-0.5, 0.3)));
}
