#include <catch2/catch.hpp>

#include "appearance/swatch_chart.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("sweeps parse and space their values evenly", "[swatch_chart]") {
    const auto s = parse_sweep("epidermis.melanosome_fraction=0.01:0.42:8");
    CHECK(s.field == "epidermis.melanosome_fraction");
    const auto v = s.values();
    REQUIRE(v.size() == 8);
    CHECK(v.front() == 0.01);
    CHECK(v.back() == Approx(0.42));
    CHECK(parse_sweep("dermis.blood_fraction=0.02:0.02:1").values() == std::vector<double>{0.02});
}

TEST_CASE("bad sweeps are input errors", "[swatch_chart]") {
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.1:5"), Catch::Contains("empty range"));
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.2:-3"), Catch::Contains("STEPS must be a whole number in [1, 1000]"));
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.2:2.5"), Catch::Contains("STEPS must be a whole number"));
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.2"), Catch::Contains("FIELD=FIRST:LAST:STEPS"));
    CHECK_THROWS_WITH(parse_sweep("0.1:0.2:3"), Catch::Contains("FIELD=FIRST:LAST:STEPS"));
    CHECK_THROWS_WITH(parse_sweep("x=a:0.2:3"), Catch::Contains("finite numbers"));
    SwatchRequest r;
    r.sweeps = {parse_sweep("epidermis.melanin=0.1:0.2:2")};
    CHECK_THROWS_WITH(compute_swatch(r), Catch::Contains("unknown key 'epidermis.melanin'"));
    r.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.5:1.5:2")};
    CHECK_THROWS_WITH(compute_swatch(r), Catch::Contains("= 1.5 is outside [0, 1]"));
}

TEST_CASE("the colour wavelengths follow the stated rule", "[swatch_chart]") {
    CHECK(swatch_wavelengths(0.3).size() == 81);
    CHECK(swatch_wavelengths(2.0).size() == 41);
    CHECK(swatch_wavelengths(0.3).front() == 380.0);
    CHECK(swatch_wavelengths(0.3).back() == 780.0);
}

TEST_CASE("a perfect white reflector is exactly the illuminant's white", "[swatch_chart]") {
    SwatchRequest r;
    r.material = SKINSPEC_TEST_INPUT_DIR "/white_reflector.toml";
    const auto chart = compute_swatch(r);
    REQUIRE(chart.patches.size() == 1);
    const auto& p = chart.patches[0];
    CHECK(p.xyz.X == Approx(chart.white.X).epsilon(1e-12));
    CHECK(p.xyz.Y == Approx(1.0).epsilon(1e-12));
    CHECK(p.lab.L == Approx(100.0).epsilon(1e-10));
    CHECK(p.delta_e_uncertainty == 0.0);
}

TEST_CASE("patches meet the colour tolerance and order by pigmentation", "[swatch_chart]") {
    SwatchRequest r;
    r.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.02:0.3:3")};
    r.delta_e = 1.0;
    const auto chart = compute_swatch(r);
    REQUIRE(chart.patches.size() == 3);
    CHECK(chart.columns == 3);
    CHECK(chart.rows == 1);
    for (const auto& p : chart.patches) {
        CHECK(p.delta_e_uncertainty <= 1.0 * 1.15);  // the allocation aims at the tolerance from estimated variances
        CHECK(p.converged);
    }
    CHECK(chart.patches[0].lab.L > chart.patches[1].lab.L + 3.0);
    CHECK(chart.patches[1].lab.L > chart.patches[2].lab.L + 3.0);
}
