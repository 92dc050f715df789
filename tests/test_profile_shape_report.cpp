#include <catch2/catch.hpp>

#include "appearance/profile_shape_report.hpp"

using namespace skinspec;

namespace {

ProfileShapeCheck check_with(double difference) {
    ProfileShapeCheck check;
    ProfileShapeError e;
    e.wavelength_nm = 550.0;
    e.photons = 100'000;
    e.largest_share_difference = difference;
    e.at_radius_mm = 0.215;
    e.walk_share_stderr = 0.003;
    e.solver_share_within_0_1_mm = 0.40;
    e.walk_share_within_0_1_mm = 0.12;
    e.solver_share_beyond_1_mm = 0.02;
    e.walk_share_beyond_1_mm = 0.08;
    check.errors.push_back(e);
    return check;
}

}  // namespace

TEST_CASE("the shape check's lines name the reference and each wavelength's shares", "[profile_shape_report]") {
    const auto lines = profile_shape_lines(check_with(0.388));
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].find("the volumetric walk, 100000 photons per wavelength") != std::string::npos);
    CHECK(lines[1] == "  550 nm: the share of R leaving within a radius r is off by up to +0.388 +- 0.003 (r = 0.215 mm); "
                      "within 0.1 mm 40 % (exact 12 %), beyond 1 mm 2 % (exact 8 %)");
    CHECK(profile_shape_lines(ProfileShapeCheck{}).empty());
    auto dark = check_with(0.0);
    dark.errors.front().compared = false;
    CHECK(profile_shape_lines(dark)[1] == "  550 nm: no light leaves within 5 mm in the walk's or the solver's profile: nothing to compare");
}

TEST_CASE("a share off by more than diffusion at its best is a warning, a check not made too", "[profile_shape_report]") {
    CHECK(profile_shape_warns(check_with(-0.2)));
    CHECK_FALSE(profile_shape_warns(check_with(0.1)));
    ProfileShapeCheck refused;
    refused.not_checked = "layer 'x' has no volumetric scattering";
    CHECK(profile_shape_warns(refused));
    CHECK(profile_shape_lines(refused) == std::vector<std::string>{"R(r) shape not checked against the exact transport: layer 'x' has no volumetric scattering"});
}

TEST_CASE("the shape check's JSON carries every figure", "[profile_shape_report]") {
    const auto json = profile_shape_json(check_with(0.388));
    CHECK(json["stopped"] == false);
    REQUIRE(json["wavelengths"].size() == 1);
    const auto& w = json["wavelengths"][0];
    CHECK(w["wavelength_nm"] == 550.0);
    CHECK(w["largest_share_difference"] == 0.388);
    CHECK(w["exact_share_beyond_1_mm"] == 0.08);
    CHECK_FALSE(json.contains("not_checked"));
}
