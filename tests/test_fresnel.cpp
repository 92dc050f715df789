#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "transport/fresnel.hpp"

using namespace skinspec;

TEST_CASE("Fresnel reflectance meets its analytic limits", "[fresnel]") {
    // Normal incidence: ((n1 - n2) / (n1 + n2))^2 (Born & Wolf Eq. 1.5.(37)).
    CHECK(fresnel_reflectance(1.0, 1.0, 1.5) == Approx(0.04).margin(1e-15));
    CHECK(fresnel_reflectance(1.0, 1.55, 1.0) == Approx(std::pow(0.55 / 2.55, 2)).margin(1e-15));
    CHECK(fresnel_reflectance(0.3, 1.4, 1.4) == 0.0);
    // Grazing incidence reflects everything.
    CHECK(fresnel_reflectance(0.0, 1.0, 1.5) == Approx(1.0));
    // Total internal reflection beyond the critical angle asin(1/1.5) = 41.8 deg.
    CHECK(fresnel_reflectance(std::cos(42.0 * std::numbers::pi / 180.0), 1.5, 1.0) == 1.0);
    CHECK(fresnel_reflectance(std::cos(41.0 * std::numbers::pi / 180.0), 1.5, 1.0) < 1.0);
    // At Brewster's angle rp = 0, so R = rs^2 / 2 with rs = (cos i - n cos t) / (cos i + n cos t).
    const double n = 1.5;
    const double brewster = std::atan(n);
    const double cos_i = std::cos(brewster);
    const double cos_t = std::cos(std::asin(std::sin(brewster) / n));
    const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    CHECK(fresnel_reflectance(cos_i, 1.0, n) == Approx(rs * rs / 2.0).epsilon(1e-12));
}

TEST_CASE("Fresnel reflectance is reciprocal", "[fresnel]") {
    for (double deg = 0.0; deg < 89.0; deg += 7.0) {
        const double ti = deg * std::numbers::pi / 180.0;
        const double tt = std::asin(std::sin(ti) / 1.4);
        CHECK(fresnel_reflectance(std::cos(ti), 1.0, 1.4) == Approx(fresnel_reflectance(std::cos(tt), 1.4, 1.0)).epsilon(1e-12));
    }
}

TEST_CASE("Snell refraction keeps unit length and obeys n1 sin1 = n2 sin2", "[fresnel]") {
    const double s = std::sin(0.6);
    const Direction d{s, 0.0, std::cos(0.6)};
    const auto t = refract(d, 1.0, 1.38);
    REQUIRE(t.has_value());
    CHECK(glm::length(*t) == Approx(1.0).epsilon(1e-14));
    CHECK(1.38 * t->x == Approx(1.0 * s).epsilon(1e-14));
    CHECK(t->z > 0.0);
    const Direction up{0.9, 0.0, -std::sqrt(1.0 - 0.81)};
    CHECK_FALSE(refract(up, 1.5, 1.0).has_value());
    CHECK(mirror(d).z == -d.z);
}
