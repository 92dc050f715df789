#include <catch2/catch.hpp>

#include "transport/random_stream.hpp"
#include "transport/skin_fold.hpp"
#include "sampling_checks.hpp"

using namespace skinspec;

TEST_CASE("skin-fold polar angles follow their CDF", "[skin_fold]") {
    for (const double sigma : {0.1, 0.5, 0.75, 0.99, 1.0}) {
        INFO("sigma = " << sigma);
        auto random = RandomStream::for_batch(9, 550.0, static_cast<std::uint64_t>(sigma * 100));
        std::vector<double> c;
        for (int i = 0; i < 100000; ++i) c.push_back(skin_fold_sample_cos(sigma, random.uniform()));
        CHECK(testing::ks_statistic(c, [sigma](double x) { return skin_fold_cdf_cos(sigma, x); }) < testing::ks_critical_1_percent);
        CHECK(skin_fold_cdf_cos(sigma, 1.0) == Approx(1.0).epsilon(1e-12));
        CHECK(skin_fold_cdf_cos(sigma, 0.0) == Approx(0.0).margin(1e-12));
        // The density integrates to 1.
        double integral = 0.0;
        for (int i = 0; i < 10000; ++i) integral += skin_fold_pdf_cos(sigma, (i + 0.5) / 10000.0) / 10000.0;
        CHECK(integral == Approx(1.0).epsilon(1e-4));
    }
    // Smaller aspect ratio: flatter folds, perturbations closer to the mirror direction.
    CHECK(skin_fold_cdf_cos(0.3, 0.9) < skin_fold_cdf_cos(0.9, 0.9));
    // The sigma -> 1 limit is continuous.
    CHECK(skin_fold_sample_cos(1.0 - 1e-6, 0.37) == Approx(skin_fold_sample_cos(1.0, 0.37)).margin(1e-5));
}

TEST_CASE("the authors' fold formula follows the CDF inverted from it by hand", "[skin_fold]") {
    // theta = arccos(sqrt((1 - u) / (u (sigma^2 - 1) + 1))): P(cos^2 <= m) = m sigma^2 / (m (sigma^2 - 1) + 1).
    for (const double sigma : {0.1, 0.5, 0.75, 1.0}) {
        INFO("sigma = " << sigma);
        auto random = RandomStream::for_batch(11, 550.0, static_cast<std::uint64_t>(sigma * 100));
        std::vector<double> c;
        for (int i = 0; i < 100000; ++i) c.push_back(skin_fold_authors_sample_cos(sigma, random.uniform()));
        CHECK(testing::ks_statistic(c, [sigma](double x) { return skin_fold_authors_cdf_cos(sigma, x); }) < testing::ks_critical_1_percent);
        CHECK(skin_fold_authors_cdf_cos(sigma, 1.0) == Approx(1.0));
    }
    // It is not the 2004 distribution (which the default keeps).
    CHECK(std::abs(skin_fold_authors_cdf_cos(0.75, 0.9) - skin_fold_cdf_cos(0.75, 0.9)) > 0.05);
}
