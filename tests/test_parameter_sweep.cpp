// --vary sweeps: the text a sweep is written as reads back as the same sweep (the swatch EXR's parameters dropped
// ":log"), and the values it stands for.
#include <catch2/catch.hpp>

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
