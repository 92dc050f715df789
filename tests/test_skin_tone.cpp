// The individual typology angle against its definition (Chardon et al. 1991) and the category bounds of Del Bino
// et al. 2006, Table 1.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "spectral/skin_tone.hpp"

using namespace skinspec;

namespace {
// The Lab whose ITA is `deg` exactly, at b* = 15.
Lab at_angle(double deg) { return Lab{50.0 + 15.0 * std::tan(deg * std::numbers::pi / 180.0), 10.0, 15.0}; }
}  // namespace

TEST_CASE("ITA is atan((L* - 50) / b*) in degrees", "[skin_tone]") {
    CHECK(skin_tone(Lab{65.0, 10.0, 15.0})->ita_deg == Approx(45.0));
    CHECK(skin_tone(Lab{50.0, 10.0, 20.0})->ita_deg == Approx(0.0).margin(1e-12));
    CHECK(skin_tone(Lab{35.0, 10.0, 15.0})->ita_deg == Approx(-45.0));
    CHECK(!skin_tone(Lab{60.0, 5.0, 0.0}));   // b* = 0: no angle in (-90, 90)
    CHECK(!skin_tone(Lab{60.0, 5.0, -3.0}));
}

TEST_CASE("the six categories of Del Bino et al. 2006", "[skin_tone]") {
    const std::pair<double, std::string_view> cases[] = {{70.0, "very light"}, {55.5, "very light"}, {54.5, "light"}, {41.5, "light"},
                                                          {40.0, "intermediate"}, {28.5, "intermediate"}, {27.0, "tan"}, {10.5, "tan"},
                                                          {9.0, "brown"}, {-29.0, "brown"}, {-31.0, "dark"}, {-60.0, "dark"}};
    for (const auto& [deg, name] : cases) {
        INFO(deg << " deg");
        CHECK(to_string(skin_tone(at_angle(deg))->category) == name);
    }
}

TEST_CASE("ITA's uncertainty: linear propagation matches a finite difference", "[skin_tone]") {
    const Lab lab{62.0, 12.0, 16.0};
    const double h = 1e-6;
    const double dL = (skin_tone(Lab{lab.L + h, lab.a, lab.b})->ita_deg - skin_tone(Lab{lab.L - h, lab.a, lab.b})->ita_deg) / (2 * h);
    const double db = (skin_tone(Lab{lab.L, lab.a, lab.b + h})->ita_deg - skin_tone(Lab{lab.L, lab.a, lab.b - h})->ita_deg) / (2 * h);
    const Lab se{0.3, 0.2, 0.4};
    CHECK(skin_tone(lab, se)->ita_stderr_deg == Approx(std::hypot(dL * se.L, db * se.b)).epsilon(1e-6));
}
