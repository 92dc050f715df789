#include <catch2/catch.hpp>

#include "spectral/chromatic_adaptation.hpp"

using namespace skinspec;

TEST_CASE("Bradford maps the source white onto the destination white", "[chromatic_adaptation]") {
    const auto d65 = white_from_chromaticity({0.3127, 0.3290});
    const auto d50 = white_from_chromaticity({0.3457, 0.3585});
    const auto w = bradford_adapt(d50, d50, d65);
    CHECK(w.X == Approx(d65.X).epsilon(1e-12));
    CHECK(w.Y == Approx(d65.Y).epsilon(1e-12));
    CHECK(w.Z == Approx(d65.Z).epsilon(1e-12));
}

TEST_CASE("Bradford D50 -> D65 matches the published matrix", "[chromatic_adaptation]") {
    // Lindbloom's Bradford D50 -> D65 matrix (whites X,Z = 0.96422, 0.82521 and 0.95047, 1.08883), first column:
    // 0.9555766, -0.0282895, 0.0122982.
    const XYZ d50{0.96422, 1.0, 0.82521};
    const XYZ d65{0.95047, 1.0, 1.08883};
    const auto col = bradford_adapt({1.0, 0.0, 0.0}, d50, d65);
    CHECK(col.X == Approx(0.9555766).margin(2e-7));
    CHECK(col.Y == Approx(-0.0282895).margin(2e-7));
    CHECK(col.Z == Approx(0.0122982).margin(2e-7));
}
