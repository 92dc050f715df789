#include <catch2/catch.hpp>

#include <algorithm>

#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

const ColorManagement& cm() { return ColorManagement::builtin(); }

XYZ white_of(IlluminantKind illuminant, ObserverKind observer = ObserverKind::cie1931_2deg) {
    return TristimulusWeights(std::vector<double>{360.0, 830.0}, illuminant, observer, OutOfRangePolicy::hold).white();
}

void check_rgb(const RGB& rgb, const RGB& expected, double margin) {
    for (int c = 0; c < 3; ++c) CHECK(rgb[c] == Approx(expected[c]).margin(margin));
}

}  // namespace

TEST_CASE("the config holds the promised spaces and displays", "[color_management]") {
    const auto spaces = cm().color_spaces();
    for (const auto* name : {"CIE-XYZ-D65", "Linear Rec.709", "sRGB", "Display P3", "Linear Rec.2020", "ACEScg"}) {
        CHECK(std::find(spaces.begin(), spaces.end(), name) != spaces.end());
    }
    const auto displays = cm().displays();
    CHECK(std::find(displays.begin(), displays.end(), "sRGB") != displays.end());
    CHECK(std::find(displays.begin(), displays.end(), "Display P3") != displays.end());
    CHECK(cm().canonical_space("acescg", "--space") == "ACEScg");
    CHECK_THROWS_WITH(cm().canonical_space("nope", "--space"), Catch::Contains("allowed: CIE-XYZ-D65"));
}

TEST_CASE("perfect white is (1, 1, 1) in every D65 RGB space and in ACEScg", "[color_management]") {
    for (const auto observer : all_observers()) {
        const auto white = white_of(IlluminantKind::d65, observer);
        for (const auto* space : {"sRGB", "Linear Rec.709", "Display P3", "Linear Rec.2020", "ACEScg"}) {
            INFO(space);
            check_rgb(cm().from_xyz(white, white, space), {1, 1, 1}, 1e-4);
        }
    }
    // Under another illuminant the Bradford step keeps white white.
    const auto a = white_of(IlluminantKind::a);
    check_rgb(cm().from_xyz(a, a, "sRGB"), {1, 1, 1}, 1e-4);
}

TEST_CASE("18 % grey encodes to the sRGB curve value", "[color_management]") {
    // IEC 61966-2-1: V = 1.055 * 0.18^(1/2.4) - 0.055 = 0.461356.
    const auto white = white_of(IlluminantKind::d65);
    const XYZ grey{0.18 * white.X, 0.18, 0.18 * white.Z};
    check_rgb(cm().from_xyz(grey, white, "sRGB"), {0.461356, 0.461356, 0.461356}, 1e-5);
}

TEST_CASE("Rec.709 primaries map to their published XYZ", "[color_management]") {
    // IEC 61966-2-1 Eq. (F.7) columns: R (0.4124, 0.2126, 0.0193), G (0.3576, 0.7152, 0.1192),
    // B (0.1805, 0.0722, 0.9505).
    check_rgb(cm().convert({1, 0, 0}, "Linear Rec.709", "CIE-XYZ-D65"), {0.4124, 0.2126, 0.0193}, 1e-4);
    check_rgb(cm().convert({0, 1, 0}, "Linear Rec.709", "CIE-XYZ-D65"), {0.3576, 0.7152, 0.1192}, 1e-4);
    check_rgb(cm().convert({0, 0, 1}, "Linear Rec.709", "CIE-XYZ-D65"), {0.1805, 0.0722, 0.9505}, 1e-4);
    // Chromaticities of the primaries: ITU-R BT.709-6 Table 1 item 1.3.
    const auto red = cm().convert({1, 0, 0}, "Linear Rec.709", "CIE-XYZ-D65");
    const auto xy = chromaticity({red[0], red[1], red[2]});
    CHECK(xy.x == Approx(0.64).margin(1e-5));
    CHECK(xy.y == Approx(0.33).margin(1e-5));
}

TEST_CASE("ACEScg matches the published AP1 matrix", "[color_management]") {
    // ACES TB-2014-004 / S-2014-004: ACEScg (AP1) -> Rec.709 linear via the Bradford D60->D65 adaptation;
    // ACEScg (1, 0, 0) -> linear Rec.709 = (1.70505, -0.13026, -0.02400).
    check_rgb(cm().convert({1, 0, 0}, "ACEScg", "Linear Rec.709"), {1.70505, -0.13026, -0.02400}, 2e-4);
}

TEST_CASE("sRGB <-> XYZ round trips", "[color_management]") {
    for (const RGB rgb : {RGB{0.2, 0.5, 0.8}, RGB{0.0, 0.0, 0.0}, RGB{1.0, 0.0, 0.5}, RGB{0.03, 0.04, 0.02}}) {
        const auto xyz = cm().convert(rgb, "sRGB", "CIE-XYZ-D65");
        check_rgb(cm().convert(xyz, "CIE-XYZ-D65", "sRGB"), rgb, 1e-5);
    }
    // Through the Bradford path too.
    const auto white = white_of(IlluminantKind::d65);
    const auto xyz = cm().convert({0.3, 0.6, 0.1}, "sRGB", "CIE-XYZ-D65");
    const auto back = cm().from_xyz({xyz[0], xyz[1], xyz[2]}, ColorManagement::reference_white(), "sRGB");
    check_rgb(back, {0.3, 0.6, 0.1}, 1e-5);
    CHECK(white.Y == 1.0);
}

TEST_CASE("display/view transform of white is white", "[color_management]") {
    check_rgb(cm().display_view({1, 1, 1}, "Linear Rec.709", "sRGB", "Standard"), {1, 1, 1}, 1e-5);
    check_rgb(cm().display_view({1, 1, 1}, "Linear Rec.709", "Display P3", "Standard"), {1, 1, 1}, 1e-5);
    CHECK_THROWS_AS(cm().display_view({1, 1, 1}, "Linear Rec.709", "NoDisplay", "Standard"), InputError);
}

TEST_CASE("a broken config is an input error", "[color_management]") {
    CHECK_THROWS_AS(ColorManagement("/nonexistent/config.ocio"), InputError);
}
