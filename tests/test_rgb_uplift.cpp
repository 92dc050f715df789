#include <catch2/catch.hpp>

#include <vector>

#include "spectral/colorimetry.hpp"
#include "spectral/input_error.hpp"
#include "spectral/rgb_uplift.hpp"

using namespace skinspec;

namespace {

std::array<double, 3> srgb_of(const UpliftedSpectrum& s) {
    std::vector<double> nm, f;
    for (int i = 360; i <= 830; ++i) {
        nm.push_back(i);
        f.push_back(s(i));
    }
    return linear_srgb(TristimulusWeights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold).integrate(f));
}

}  // namespace

TEST_CASE("linear sRGB of the D65 white is 1, 1, 1 (IEC 61966-2-1)", "[rgb_uplift]") {
    const std::vector<double> nm{380.0, 500.0, 780.0};
    const auto white = linear_srgb(TristimulusWeights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold).white());
    for (const double v : white) CHECK(v == Approx(1.0).margin(2e-3));
}

TEST_CASE("an uplifted RGB is a smooth spectrum with that RGB, and a grey one is flat at its value", "[rgb_uplift]") {
    // Grey: the sigmoid at c = 0 is 1/2, times the scale 2 max (Jakob & Hanika 2019 Eq. 3; pbrt-v4's unbounded scaling).
    const UpliftedSpectrum grey({0.37, 0.37, 0.37});
    CHECK(grey.scale() == Approx(0.74));
    for (const double nm : {360.0, 451.0, 600.0, 830.0}) CHECK(grey(nm) == Approx(0.37).epsilon(2e-3));
    // Coefficients as skin exports hold them, from grey to saturated (a zero-free channel ratio of 1:30): the
    // spectrum's own sRGB under D65 is the one asked for.
    for (const auto& rgb : std::vector<std::array<double, 3>>{{0.5, 0.2, 0.1}, {0.0185, 0.261, 0.491}, {1.43, 3.0, 5.09}, {110.2, 100.0, 100.0}}) {
        const UpliftedSpectrum s(rgb);
        const auto back = srgb_of(s);
        for (std::size_t c = 0; c < 3; ++c) CHECK(back[c] == Approx(rgb[c]).epsilon(1e-6));
        for (int nm = 360; nm <= 830; nm += 10) CHECK((s(nm) >= 0.0 && s(nm) <= s.scale()));
    }
    CHECK(UpliftedSpectrum({0.0, 0.0, 0.0})(500.0) == 0.0);
    CHECK_THROWS_AS(UpliftedSpectrum({0.1, -0.2, 0.3}), InputError);
}
