#include <catch2/catch.hpp>

#include <cmath>

#include "transport/time_left.hpp"

using namespace skinspec;

TEST_CASE("a steady run's time left is its remaining work over its rate, counted from after start-up", "[time_left]") {
    TimeLeft t;
    CHECK_FALSE(t.update(0.2, 0.0).has_value());
    // 2 s of start-up, then 1 % of the work per second: 100 s of work after start-up.
    const auto share_at = [](double s) { return s < 2.0 ? 0.001 : 0.001 + 0.01 * (s - 2.0); };
    CHECK_FALSE(t.update(1.0, share_at(1.0)).has_value());  // the window is too short yet
    for (double s = 1.1; s < 30.0; s += 0.1) t.update(s, share_at(s));
    const auto left = t.update(30.0, share_at(30.0));
    REQUIRE(left.has_value());
    const double truth = (1.0 - share_at(30.0)) / 0.01;
    CHECK(std::abs(*left - truth) < 0.15 * truth);  // start-up's slow second still weighs in the rate
    CHECK(t.update(102.1, 1.0).value() == 0.0);
}

TEST_CASE("a share that jumps back and forth between wavelengths moves the estimate smoothly and never back in the work", "[time_left]") {
    TimeLeft t;
    // Ten wavelengths of 10 s each; within one, the share from rays against a planner's estimate overshoots to the
    // next wavelength's share and falls back when the estimate is revised (what the bar showed as 14 s / 1 min 50 s).
    std::optional<double> previous;
    double largest_step = 0.0;
    for (double s = 0.6; s < 95.0; s += 0.25) {
        const double wavelength = std::floor(s / 10.0), within = std::fmod(s, 10.0) / 10.0;
        const double share = (wavelength + (within < 0.3 ? 3.0 * within : 0.9 + 0.1 * within)) / 10.0;
        const auto left = t.update(s, share);
        if (previous && left) largest_step = std::max(largest_step, std::abs(*left - (*previous - 0.25)));
        previous = left;
    }
    REQUIRE(previous.has_value());
    CHECK(largest_step < 5.0);  // seconds, at 4 reports a second
}

TEST_CASE("the share of work done stays between the units finished and those plus the ones in progress", "[time_left]") {
    CHECK(work_share({0, 0, 3, 10}) == Approx(0.3));
    CHECK(work_share({500, 1000, 3, 10}) == Approx(0.4));  // rays say half the work: not past the current unit
    CHECK(work_share({10, 1000, 3, 10}) == Approx(0.3));   // nor before the units finished
    CHECK(work_share({350, 1000, 3, 10}) == Approx(0.35));
    CHECK(work_share({0, 0, 0, 0}) == 1.0);
    // Eleven wavelengths traced at once (a walk's round): the rays are the measure, none finished until the end.
    CHECK(work_share({26'000'000, 55'000'000, 0, 11, 11}) == Approx(26.0 / 55.0));
}

TEST_CASE("a walk's progress through run_batches gives an estimate near the truth", "[time_left]") {
    // Eleven wavelengths of 5e6 rays each, traced at once at a steady rate over 10 s, reported as run_batches
    // reports them: before, the share stopped at 1/11 and the estimate rose to 8 min 30 s for a 6 s run.
    TimeLeft t;
    std::optional<double> left;
    for (double s = 0.1; s < 5.0; s += 0.1) {
        const auto rays = static_cast<std::uint64_t>(55e6 * s / 10.0);
        left = t.update(s, work_share({rays, 55'000'000, 0, 11, 11}));
    }
    REQUIRE(left.has_value());
    CHECK(*left == Approx(5.0).epsilon(0.1));
}

TEST_CASE("a budget so large that the share barely moves is still estimated after a longer look", "[time_left]") {
    // --rays 1125899906842624: the share grows by ~1e-9 per second and never by min_share_step; after long_window_s
    // of steady growth the estimate is the remaining work over the rate (31.7 years here), not "measuring" for ever.
    TimeLeft t;
    const double rate = 1e-9;  // share per second
    std::optional<double> left;
    for (double s = 0.1; s <= TimeLeft::long_window_s + 1.0; s += 0.1) {
        left = t.update(s, rate * s);
        if (s < TimeLeft::startup_s + TimeLeft::long_window_s - 0.05) CHECK_FALSE(left.has_value());
    }
    REQUIRE(left.has_value());
    CHECK(*left == Approx(1.0 / rate).epsilon(1e-3));
}
