#include <catch2/catch.hpp>

#include <cmath>

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
        // The sampler is the paper's formula (Krishnaswamy & Baranoski 2004, the skin-fold perturbation), written here:
        // theta = arccos(sqrt((sigma^2 / sqrt(sigma^4 + (1 - sigma^4) u) - 1) / (sigma^2 - 1))); sigma = 1 its limit sqrt(u).
        for (const double u : {0.01, 0.2, 0.5, 0.8, 0.99}) {
            const double s2 = sigma * sigma;
            const double paper = sigma == 1.0 ? std::sqrt(u) : std::sqrt((s2 / std::sqrt(s2 * s2 + (1.0 - s2 * s2) * u) - 1.0) / (s2 - 1.0));
            CHECK(skin_fold_sample_cos(sigma, u) == Approx(paper).epsilon(1e-12));
            // and the CDF inverts it: P(cos <= sample(u)) = u (the cosine grows with u).
            CHECK(skin_fold_cdf_cos(sigma, paper) == Approx(u).margin(1e-9));
        }
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
        // The formula above, written here, not the library's CDF: P(cos <= x) = x^2 sigma^2 / (x^2 (sigma^2 - 1) + 1).
        const auto formula = [sigma](double x) { return x * x * sigma * sigma / (x * x * (sigma * sigma - 1.0) + 1.0); };
        CHECK(testing::ks_statistic(c, formula) < testing::ks_critical_1_percent);
        CHECK(skin_fold_authors_cdf_cos(sigma, 0.6) == Approx(formula(0.6)));
        CHECK(skin_fold_authors_cdf_cos(sigma, 1.0) == Approx(1.0));
    }
    // It is not the 2004 distribution (which the default keeps).
    CHECK(std::abs(skin_fold_authors_cdf_cos(0.75, 0.9) - skin_fold_cdf_cos(0.75, 0.9)) > 0.05);
}
