// --vary sweeps: the text a sweep is written as reads back as the same sweep (the swatch EXR's parameters dropped
// ":log"), and the values it stands for.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "materials/parameter_sweep.hpp"

using namespace skinspec;

TEST_CASE("a sweep's text reads back as the same sweep, log spacing included", "[parameter_sweep]") {
    for (const auto* text : {"epidermis.melanosome_fraction=0.01:0.42:8:log", "dermis.blood_fraction=0.002:0.05:3", "epidermis.thickness_cm=0.1:0.1:1"}) {
        INFO(text);
        const auto sweep = parse_sweep(text);
        CHECK(sweep.text() == text);
        const auto again = parse_sweep(sweep.text());
        CHECK(again.values() == sweep.values());
    }
    const auto log = parse_sweep("epidermis.melanosome_fraction=0.01:1:3:log").values();
    REQUIRE(log.size() == 3);
    CHECK(log[1] == Approx(0.1));  // evenly spaced in the logarithm
}

TEST_CASE("sweeps over ranges near the doubles' limits stay finite", "[parameter_sweep]") {
    // last / first and last - first overflow here (1e600, 2e308); the values must not (a member was '= inf').
    const auto wide_log = parse_sweep("f=1e-300:1e300:3:log").values();
    REQUIRE(wide_log.size() == 3);
    for (const double v : wide_log) CHECK(std::isfinite(v));
    CHECK(wide_log[0] == Approx(1e-300).epsilon(1e-12));
    CHECK(wide_log[1] == Approx(1.0).epsilon(1e-12));
    CHECK(wide_log[2] == Approx(1e300).epsilon(1e-12));
    const auto wide = parse_sweep("f=-1.5e308:1.5e308:3").values();
    CHECK(wide == std::vector<double>{-1.5e308, 0.0, 1.5e308});
}
