#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "transport/ray_tally.hpp"

using namespace skinspec;

namespace {

// `batches` batches of `rays` rays each; every ray scores 1 with probability p in channel 0 (per-ray squares) and the
// same value in channel 1 (batch means).
RayTally bernoulli(double p, std::size_t batches, std::size_t rays) {
    std::mt19937_64 engine(12345);
    std::bernoulli_distribution hit(p);
    RayTally total(2);
    for (std::size_t b = 0; b < batches; ++b) {
        RayTally batch(2);
        batch.use_batch_means(1, 1);
        RayScore score(2);
        for (std::size_t i = 0; i < rays; ++i) {
            const double v = hit(engine) ? 1.0 : 0.0;
            if (v > 0.0) score.add(0, v);
            batch.add_to_batch(1, v);
            batch.add_ray(score);
        }
        total.merge(batch);
    }
    return total;
}

}  // namespace

TEST_CASE("per-ray standard errors of 0/1 scores are sqrt(p (1 - p) / (N - 1))", "[ray_tally]") {
    const auto t = bernoulli(0.3, 20, 500);
    const auto e = t.estimate(0);
    const double n = static_cast<double>(t.rays());
    CHECK(e.stderr == Approx(std::sqrt(e.value * (1.0 - e.value) / (n - 1.0))).epsilon(1e-12));
}

TEST_CASE("batch means give the mean exactly and the binomial standard error within their own precision", "[ray_tally]") {
    // 400 batches estimate the standard error to 1 / sqrt(2 (B - 1)) = 3.5 %; 4 of those.
    const auto t = bernoulli(0.3, 400, 250);
    const auto per_ray = t.estimate(0);
    const auto batched = t.estimate(1);
    CHECK(batched.value == Approx(per_ray.value).epsilon(1e-15));
    const double exact = std::sqrt(0.3 * 0.7 / static_cast<double>(t.rays()));
    CHECK(batched.stderr == Approx(exact).epsilon(0.14));
    CHECK(batched.stderr == Approx(per_ray.stderr).epsilon(0.14));
}

TEST_CASE("batch means: equal means give no error, unequal batch sizes are weighted, one batch gives 0", "[ray_tally]") {
    RayTally total(1);
    for (const std::size_t rays : {3u, 50u, 7u}) {
        RayTally batch(1);
        batch.use_batch_means(0, 1);
        RayScore score(1);
        for (std::size_t i = 0; i < rays; ++i) {
            batch.add_to_batch(0, 0.25);
            batch.add_ray(score);
        }
        total.merge(batch);
    }
    CHECK(total.estimate(0).value == Approx(0.25).epsilon(1e-15));
    CHECK(total.estimate(0).stderr < 1e-12);
    const auto one = bernoulli(0.5, 1, 100);
    CHECK(one.estimate(1).stderr == 0.0);
    CHECK(one.estimate(0).stderr > 0.0);
}
