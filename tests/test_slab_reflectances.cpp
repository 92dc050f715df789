#include <catch2/catch.hpp>

#include <cmath>

#include "inverse/iad/slab_reflectances.hpp"

using namespace skinspec;

TEST_CASE("unscattered light: the incoherent slab of Fresnel faces and Beer-Lambert", "[iad]") {
    // Bare slab of 1.5 in air at normal incidence: F = 0.04, R = F + (1 - F)^2 F e^-2b / (1 - F^2 e^-2b),
    // T = (1 - F)^2 e^-b / (1 - F^2 e^-2b) (Born & Wolf, incoherent plate).
    SlabSetup s;
    s.sample_index = 1.5;
    const double f = 0.04, e = std::exp(-0.7);
    const auto u = unscattered(0.7, s);
    CHECK(u.r == Approx(f + (1 - f) * (1 - f) * f * e * e / (1 - f * f * e * e)).epsilon(1e-12));
    CHECK(u.t == Approx((1 - f) * (1 - f) * e / (1 - f * f * e * e)).epsilon(1e-12));
    // Oblique (40 deg): Fresnel's equations for unpolarised light (Born & Wolf 1.5.3) and the longer refracted path.
    s.incidence_deg = 40.0;
    const double ci = std::cos(40.0 * std::acos(-1.0) / 180.0), si = std::sqrt(1 - ci * ci);
    const double ct = std::sqrt(1.0 - (si / 1.5) * (si / 1.5));
    const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
    const double fo = 0.5 * (rs * rs + rp * rp), eo = std::exp(-0.7 / ct);
    CHECK(unscattered(0.7, s).t == Approx((1 - fo) * (1 - fo) * eo / (1 - fo * fo * eo * eo)).epsilon(1e-12));
}

TEST_CASE("slab reflections: a non-scattering slab is its unscattered light, a non-absorbing one conserves energy", "[iad]") {
    SlabSetup s;
    s.sample_index = 1.4;
    s.slide_index = 1.5;
    s.slide_thickness_mm = 1.0;
    AdCache cache;
    // a = 0: everything that leaves is unscattered (the closed form and adding-doubling agree).
    const auto clear = slab_reflectances({0.0, 1.3, 0.0}, s, 24, cache);
    CHECK(clear.ur1 == Approx(clear.ru).epsilon(1e-5));
    CHECK(clear.ut1 == Approx(clear.tu).epsilon(1e-5));
    // a = 1: R + T = 1 for the beam and for diffuse light.
    for (const double g : {0.0, 0.9}) {
        const auto white = slab_reflectances({1.0, 3.0, g}, s, 24, cache);
        CHECK(white.ur1 + white.ut1 == Approx(1.0).epsilon(1e-9));
        CHECK(white.uru + white.utu == Approx(1.0).epsilon(1e-9));
        CHECK(white.ru < white.ur1);
    }
}
