#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <math.h>
#include <numbers>
#include <vector>

#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/multipole.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();

// 2 pi int_0^r_max f(r) J0(k r) r dr by the midpoint rule on a fine grid.
template <typename F>
double hankel(F&& f, double k, double r_max, double dr) {
    double sum = 0.0;
    for (double r = 0.5 * dr; r < r_max; r += dr) sum += 2.0 * std::numbers::pi * f(r) * ::j0(k * r) * r * dr;
    return sum;
}
}  // namespace

TEST_CASE("a semi-infinite multipole is Jensen's dipole", "[multipole]") {
    for (const auto& m : {DipoleMedium{2.19, 0.0021, 1.5}, DipoleMedium{0.74, 0.032, 1.3}, DipoleMedium{1.0, 0.5, 0.8}}) {
        const Dipole dipole(m);
        const Multipole multipole({m.reduced_scattering, m.absorption, inf, diffuse_fresnel_reflectance(m.eta), 0.0});
        // The closed form of Jensen et al. 2001 Sec. 2.4 against the sum of source integrals.
        CHECK(multipole.total_reflectance() == Approx(dipole.total_reflectance()).epsilon(1e-12));
        CHECK(multipole.total_transmittance() == 0.0);
        for (const double r : {0.0, 0.1, 1.0, 10.0}) CHECK(multipole.radial_reflectance(r) == Approx(dipole.radial_reflectance(r)).epsilon(1e-12));
    }
}

TEST_CASE("without absorption a slab reflects and transmits everything, split as diffusion theory says", "[multipole]") {
    // sigma_a = 0: T = (l + z_b(0)) / (d + z_b(0) + z_b(d)) (the steady-state diffusion solution between the
    // extrapolated boundaries), R = 1 - T.
    for (const double d : {2.0, 5.0, 40.0}) {
        for (const auto& faces : {std::pair{0.0, 0.0}, std::pair{0.44, 0.1}, std::pair{0.6, 0.6}}) {
            const Multipole m({1.0, 0.0, d, faces.first, faces.second});
            const double dc = 1.0 / 3.0;
            const double zb0 = 2.0 * (1 + faces.first) / (1 - faces.first) * dc, zbd = 2.0 * (1 + faces.second) / (1 - faces.second) * dc;
            const double t = (1.0 + zb0) / (d + zb0 + zbd);
            INFO("d " << d << " faces " << faces.first << " " << faces.second);
            CHECK(m.total_transmittance() == Approx(t).epsilon(1e-12));
            CHECK(m.total_reflectance() + m.total_transmittance() == Approx(1.0).epsilon(1e-12));
        }
    }
}

TEST_CASE("profiles integrate to the closed-form totals and transform as the closed form says", "[multipole]") {
    for (const double d : {2.0, 10.0, 20.0}) {
        const Multipole m({0.99, 0.01, d, diffuse_fresnel_reflectance(1.4), diffuse_fresnel_reflectance(1.4)});
        const auto r_of = [&](double r) { return m.radial_reflectance(r); };
        const auto t_of = [&](double r) { return m.radial_transmittance(r); };
        INFO("slab of " << d << " mfp");
        CHECK(hankel(r_of, 0.0, 150.0, 4e-3) == Approx(m.total_reflectance()).epsilon(1e-3));
        CHECK(hankel(t_of, 0.0, 150.0, 4e-3) == Approx(m.total_transmittance()).epsilon(1e-3));
        for (const double k : {0.3, 1.0, 3.0}) {
            CHECK(hankel(r_of, k, 150.0, 4e-3) == Approx(m.reflectance_transform(k)).margin(1e-4));
            CHECK(hankel(t_of, k, 150.0, 4e-3) == Approx(m.transmittance_transform(k)).margin(1e-4));
        }
    }
}

TEST_CASE("thick slabs become the dipole, pairs are chosen by convergence", "[multipole]") {
    const double f = diffuse_fresnel_reflectance(1.3);
    const Multipole thick({1.0, 0.05, 100.0, f, f});
    const Dipole dipole({1.0, 0.05, 1.3});
    for (const double r : {0.0, 1.0, 5.0}) CHECK(thick.radial_reflectance(r) == Approx(dipole.radial_reflectance(r)).epsilon(1e-6));
    CHECK(thick.total_transmittance() < 1e-10);
    const std::vector<double> radii{0.0, 1.0, 5.0};
    const auto thin_profile = Multipole({1.0, 0.05, 2.0, f, f}).reflectance_profile(radii);
    const auto thick_profile = thick.reflectance_profile(radii);
    CHECK(thin_profile.converged);
    CHECK(thick_profile.max_pairs < thin_profile.max_pairs);  // a thin slab needs more images
    CHECK(thin_profile.max_pairs < 1000);
}

TEST_CASE("multipole stress: extreme slabs stay finite and in range", "[multipole][stress]") {
    const double f = diffuse_fresnel_reflectance(1.4);
    const double f_inner = diffuse_fresnel_reflectance(0.7);  // eta < 1: leaving into a denser medium
    for (const double d : {1e-9, 1e-3, 0.5, 2.0, 1e3, 1e9}) {
        for (const double sa : {0.0, 1e-9, 0.01, 1.0, 100.0}) {
            for (const double ss : {1e-12, 1e-3, 1.0, 1e4}) {
                for (const auto& faces : {std::pair{0.0, 0.0}, std::pair{f, f_inner}, std::pair{0.999, 0.999}}) {
                    const Multipole m({ss, sa, d, faces.first, faces.second});
                    const double r = m.total_reflectance(), t = m.total_transmittance();
                    INFO("d " << d << " sa " << sa << " ss " << ss << " faces " << faces.first);
                    CHECK(std::isfinite(r));
                    CHECK(std::isfinite(t));
                    CHECK(r >= -1e-12);
                    CHECK(t >= -1e-12);
                    CHECK(r + t <= 1.0 + 1e-9);
                    for (const double radius : {0.0, 0.5 * m.mean_free_path(), 10.0 * m.mean_free_path()}) {
                        CHECK(std::isfinite(m.radial_reflectance(radius)));
                        CHECK(std::isfinite(m.radial_transmittance(radius)));
                    }
                }
            }
        }
    }
}

TEST_CASE("multipole rejects bad slabs with clear messages", "[multipole]") {
    CHECK_THROWS_WITH(Multipole({-1.0, 0.1, 1.0, 0.0, 0.0}), Catch::Contains("reduced scattering = -1 is outside [0, inf)"));
    CHECK_THROWS_WITH(Multipole({1.0, NAN, 1.0, 0.0, 0.0}), Catch::Contains("absorption = nan is outside [0, inf)"));
    CHECK_THROWS_WITH(Multipole({1.0, 0.1, 0.0, 0.0, 0.0}), Catch::Contains("thickness = 0 is outside (0, inf]"));
    CHECK_THROWS_WITH(Multipole({1.0, 0.1, 1.0, 1.0, 0.0}), Catch::Contains("top internal reflectance = 1 is outside [0, 1)"));
    CHECK_THROWS_WITH(Multipole({0.0, 0.0, 1.0, 0.0, 0.0}), Catch::Contains("sigma_t' = 0 is outside (0, inf)"));
}
