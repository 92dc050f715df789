#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include "transport/ray_planner.hpp"

using namespace skinspec;

namespace {

// A Bernoulli(p) "ray" with p depending on the wavelength: its mean and standard error are known exactly.
void bernoulli(std::size_t w, std::uint64_t, RandomStream& random, std::uint64_t rays, RayTally& tally) {
    RayScore score(1);
    const double p = 0.1 + 0.2 * static_cast<double>(w);
    for (std::uint64_t i = 0; i < rays; ++i) {
        if (random.uniform() < p) score.add(0, 1.0);
        tally.add_ray(score);
    }
}

SpectralRequest request() {
    SpectralRequest r;
    r.wavelengths = WavelengthGrid::list({400.0, 500.0, 600.0});
    return r;
}

}  // namespace

TEST_CASE("a fixed budget traces exactly that many rays per wavelength", "[spectral_driver]") {
    auto r = request();
    r.max_rays_per_wavelength = 10'000;
    const auto out = run_batches(r, 1, {0}, bernoulli);
    for (std::size_t w = 0; w < 3; ++w) {
        CHECK(out.tallies[w].rays() == 10'000);
        CHECK(out.finished[w]);
        const auto e = out.tallies[w].estimate(0);
        const double p = 0.1 + 0.2 * static_cast<double>(w);
        CHECK(std::abs(e.value - p) < 5.0 * std::sqrt(p * (1 - p) / 1e4));
        CHECK(e.stderr == Approx(std::sqrt(p * (1 - p) / 1e4)).epsilon(0.05));
    }
}

TEST_CASE("adaptive stopping meets the target or spends the budget", "[spectral_driver]") {
    auto r = request();
    r.stderr_target = 0.002;
    r.max_rays_per_wavelength = 1'000'000;
    const auto out = run_batches(r, 1, {0}, bernoulli);
    for (std::size_t w = 0; w < 3; ++w) {
        CHECK(out.converged[w]);
        CHECK(out.tallies[w].estimate(0).stderr <= 0.002);
        const double p = 0.1 + 0.2 * static_cast<double>(w);
        // Not wildly more than needed: p(1-p)/0.002^2 rays, with batch rounding and the 10 % margin.
        CHECK(out.tallies[w].rays() < 1.3 * p * (1 - p) / 4e-6 + 8 * r.rays_per_batch);
    }
    r.max_rays_per_wavelength = 20'000;
    const auto capped = run_batches(r, 1, {0}, bernoulli);
    CHECK_FALSE(capped.converged[2]);
    CHECK(capped.finished[2]);
    CHECK(capped.tallies[2].rays() == 20'000);
}

TEST_CASE("results are identical for 1 and 2 threads", "[spectral_driver]") {
    auto r = request();
    r.stderr_target = 0.003;
    r.max_rays_per_wavelength = 1'000'000;
    const auto run = [&](int threads) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
        return run_batches(r, 1, {0}, bernoulli);
    };
    const auto one = run(1);
    const auto two = run(2);
    for (std::size_t w = 0; w < 3; ++w) {
        CHECK(one.tallies[w].rays() == two.tallies[w].rays());
        CHECK(one.tallies[w].estimate(0).value == two.tallies[w].estimate(0).value);
        CHECK(one.tallies[w].estimate(0).stderr == two.tallies[w].estimate(0).stderr);
    }
}

TEST_CASE("cancellation stops between batches and reports what finished", "[spectral_driver]") {
    auto r = request();
    r.max_rays_per_wavelength = 100'000;
    CancelFlag cancel{true};
    r.cancel = &cancel;
    const auto out = run_batches(r, 1, {0}, bernoulli);
    CHECK(out.cancelled);
    for (std::size_t w = 0; w < 3; ++w) CHECK_FALSE(out.finished[w]);
    std::size_t calls = 0;
    cancel = false;
    r.on_progress = [&](const Progress& p) {
        ++calls;
        CHECK(p.wavelengths_total == 3);
    };
    const auto done = run_batches(r, 1, {0}, bernoulli);
    CHECK_FALSE(done.cancelled);
    CHECK(calls > 0);
}
