#include <catch2/catch.hpp>

#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/rough_surface.hpp"
#include "transport/fresnel.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {
// Hemispherical (cosine-weighted) average of the smooth Fresnel reflectance, 2 int F(mu) mu dmu.
double smooth_average(double n_from, double n_to) {
    const int n = 200000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        sum += 2.0 * fresnel_reflectance(mu, n_from, n_to) * mu / n;
    }
    return sum;
}
}  // namespace

TEST_CASE("a nearly smooth Torrance-Sparrow surface is the Fresnel interface", "[rough]") {
    for (const double n : {1.3, 1.4, 1.55}) {
        const RoughSurface s(1e-4, 1.0, n);
        INFO("n " << n);
        CHECK(s.internal_diffuse_reflectance() == Approx(smooth_average(n, 1.0)).margin(2e-3));
        for (const double mu : {1.0, 0.7, 0.3}) CHECK(s.entry_transmittance(mu) == Approx(1.0 - fresnel_reflectance(mu, 1.0, n)).margin(1e-3));
        // The polynomial F_dr of Donner & Jensen 2005 Eq. 8 approximates the same average.
        CHECK(diffuse_fresnel_reflectance(n) == Approx(smooth_average(n, 1.0)).margin(0.01));
    }
}

TEST_CASE("rough surfaces stay physical", "[rough]") {
    for (const double m : {0.05, 0.2, 0.5, 1.0, 2.0}) {
        const RoughSurface s(m, 1.0, 1.4);
        INFO("m " << m);
        CHECK(s.internal_diffuse_reflectance() > 0.0);
        CHECK(s.internal_diffuse_reflectance() < 1.0);
        for (const double mu : {1.0, 0.5, 0.05}) {
            CHECK(s.entry_transmittance(mu) > 0.0);
            CHECK(s.entry_transmittance(mu) <= 1.0);
        }
        // From inside, total internal reflection makes the surface reflect more than from outside.
        CHECK(s.internal_diffuse_reflectance() > 1.0 - s.entry_transmittance(0.7));
    }
    // Roughness removes part of the total internal reflection seen from inside.
    CHECK(RoughSurface(0.5, 1.0, 1.4).internal_diffuse_reflectance() < RoughSurface(0.01, 1.0, 1.4).internal_diffuse_reflectance());
    CHECK_THROWS_WITH(RoughSurface(0.0, 1.0, 1.4), Catch::Contains("roughness = 0 is outside (0, 2]"));
    CHECK_THROWS_WITH(RoughSurface(0.3, 1.0, 0.5), Catch::Contains("refractive index = 0.5 is outside [1, 5]"));
}
