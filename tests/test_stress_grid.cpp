#include <catch2/catch.hpp>

#include "studies/benchmark/stress_grid.hpp"

using namespace skinspec;

TEST_CASE("the short stress grid: every solver finite, in [0, 1], conserving energy, ordered, in bounded time", "[stress_grid]") {
    StressOptions options;
    options.max_seconds_per_case = 30.0;
    const auto report = run_stress_grid(options);
    for (const auto& o : report.outcomes) {
        INFO(o.solver << ": " << o.name << ": " << o.failure);
        CHECK(o.passed);
    }
    CHECK(report.outcomes.size() > 500);
    CHECK_FALSE(report.partial);
    // Cases outside the tables or the diffusion fits are refused with the range, never computed.
    std::size_t refused = 0;
    for (const auto& o : report.outcomes) refused += o.limit.find("is outside") != std::string::npos ? 1 : 0;
    CHECK(refused > 10);
}
