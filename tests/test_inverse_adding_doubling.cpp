#include <catch2/catch.hpp>

#include <cmath>

#include "inverse/iad/inverse_adding_doubling.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

SlabSetup setup_with(double spheres, bool slides) {
    SlabSetup s;
    s.sample_index = 1.4;
    s.sample_thickness_mm = 2.0;
    s.spheres = spheres;
    if (slides) {
        s.slide_index = 1.5;
        s.slide_thickness_mm = 1.0;
    }
    return s;
}

// (a, b, g) of a slab of thickness d [mm] with these coefficients [1/mm].
SlabOptics optics_of(double mu_a, double mu_s_reduced, double g, double d) {
    const double mu_s = mu_s_reduced / (1.0 - g);
    return {mu_s / (mu_a + mu_s), (mu_a + mu_s) * d, g};
}

}  // namespace

TEST_CASE("iad recovers mu_a and mu_s' of its own forward slabs to 1e-4 with 0/1/2 spheres and with or without slides", "[iad]") {
    SlabInverter inverter(IadSettings{});
    for (const double spheres : {0.0, 1.0, 2.0}) {
        for (const bool slides : {false, true}) {
            for (const auto& [mu_a, mu_s_reduced] : {std::pair{0.05, 1.5}, std::pair{0.5, 3.0}, std::pair{0.01, 0.3}}) {
                auto s = setup_with(spheres, slides);
                s.g = 0.8;
                const auto measured = inverter.predict(optics_of(mu_a, mu_s_reduced, s.g, s.sample_thickness_mm), s);
                const SlabMeasurement m{std::nullopt, measured.m_r, measured.m_t, std::nullopt, s, "test"};
                const auto r = inverter.invert(m, {});
                INFO("spheres " << spheres << ", slides " << slides << ", mu_a " << mu_a << ", mu_s' " << mu_s_reduced);
                REQUIRE(r.reachable);
                CHECK(*r.mu_a_per_mm == Approx(mu_a).epsilon(1e-4));
                CHECK(*r.mu_s_reduced_per_mm == Approx(mu_s_reduced).epsilon(1e-4));
                CHECK(r.unknowns == IadUnknowns::albedo_thickness);
            }
        }
    }
}

TEST_CASE("iad with the unscattered transmission also recovers g", "[iad]") {
    SlabInverter inverter(IadSettings{});
    auto s = setup_with(2.0, true);
    const auto optics = optics_of(0.1, 1.0, 0.7, 1.0);
    s.sample_thickness_mm = 1.0;
    const auto measured = inverter.predict(optics, s);
    const double m_u = unscattered(optics.optical_thickness, s).t;
    const auto r = inverter.invert({std::nullopt, measured.m_r, measured.m_t, m_u, s, "test"}, {});
    REQUIRE(r.reachable);
    CHECK(r.unknowns == IadUnknowns::albedo_anisotropy);
    CHECK(r.optics.g == Approx(0.7).epsilon(1e-4));
    CHECK(*r.mu_a_per_mm == Approx(0.1).epsilon(1e-4));
    CHECK(*r.mu_s_reduced_per_mm == Approx(1.0).epsilon(1e-4));
    CHECK(*r.fitted_m_u == Approx(m_u).epsilon(1e-9));
}

TEST_CASE("iad with M_R alone: the albedo of an infinitely thick slab", "[iad]") {
    SlabInverter inverter(IadSettings{});
    const auto s = setup_with(0.0, false);
    const auto thick = inverter.predict({0.95, 1e6, 0.0}, s);
    const auto r = inverter.invert({std::nullopt, thick.m_r, std::nullopt, std::nullopt, s, "test"}, {});
    CHECK(r.unknowns == IadUnknowns::albedo_only);
    CHECK(r.optics.albedo == Approx(0.95).epsilon(1e-6));
    CHECK_FALSE(r.mu_a_per_mm.has_value());  // not separable from mu_s without a thickness
    // M_T = 0 (iad's files) is the same case.
    CHECK(inverter.invert({std::nullopt, thick.m_r, 0.0, 0.0, s, "test"}, {}).unknowns == IadUnknowns::albedo_only);
}

TEST_CASE("iad reports a measurement no slab produces, with the closest one that can", "[iad]") {
    SlabInverter inverter(IadSettings{});
    const auto s = setup_with(0.0, false);
    // R + T above 1 - (what the faces must reflect): beyond any non-absorbing slab.
    const auto r = inverter.invert({std::nullopt, 0.6, 0.5, std::nullopt, s, "f.rxt:9"}, {});
    CHECK_FALSE(r.reachable);
    CHECK_THAT(r.unreachable, Catch::Contains("f.rxt:9: M_R = 0.6, M_T = 0.5 cannot be produced") && Catch::Contains("the closest (relative to each measurement) is"));
    // Below the faces' own reflection.
    CHECK_FALSE(inverter.invert({std::nullopt, 0.01, 0.5, std::nullopt, s, "x"}, {}).reachable);
}

TEST_CASE("iad refuses measurements that determine nothing", "[iad]") {
    SlabInverter inverter(IadSettings{});
    const auto s = setup_with(0.0, false);
    CHECK_THROWS_WITH(inverter.invert({std::nullopt, std::nullopt, 0.3, std::nullopt, s, "x"}, {}), Catch::Contains("no M_R"));
    CHECK_THROWS_WITH(inverter.invert({std::nullopt, 1.2, 0.3, std::nullopt, s, "x"}, {}), Catch::Contains("M_R = 1.2 is outside [0, 1]"));
    CHECK_THROWS_WITH(inverter.invert({std::nullopt, 0.3, std::nullopt, 0.1, s, "x"}, {}), Catch::Contains("M_U without M_T"));
    CHECK_THROWS_WITH(inverter.invert({std::nullopt, 0.3, 0.3, 0.99, s, "x"}, {}), Catch::Contains("M_U = 0.99 is at or above"));
}

TEST_CASE("iad uncertainties: the measurements' propagated match re-inverting perturbed measurements", "[iad]") {
    // Independent check of the linear propagation: invert M_R +- d and M_T +- d and compare the spread.
    SlabInverter inverter(IadSettings{});
    const auto s = setup_with(1.0, true);
    const auto measured = inverter.predict(optics_of(0.2, 2.0, 0.0, s.sample_thickness_mm), s);
    const double u = 1e-3;
    const auto r = inverter.invert({std::nullopt, measured.m_r, measured.m_t, std::nullopt, s, "x"}, {u, u, 0.0});
    REQUIRE(r.mu_a_stderr_per_mm.has_value());
    const auto shifted = [&](double dr, double dt) {
        return inverter.invert({std::nullopt, measured.m_r + dr, measured.m_t + dt, std::nullopt, s, "x"}, {});
    };
    const auto rp = shifted(u, 0.0), tp = shifted(0.0, u);
    const double mua_spread = std::hypot(*rp.mu_a_per_mm - *r.mu_a_per_mm, *tp.mu_a_per_mm - *r.mu_a_per_mm);
    const double mus_spread = std::hypot(*rp.mu_s_reduced_per_mm - *r.mu_s_reduced_per_mm, *tp.mu_s_reduced_per_mm - *r.mu_s_reduced_per_mm);
    CHECK(*r.mu_a_stderr_per_mm == Approx(mua_spread).epsilon(0.02));
    CHECK(*r.mu_s_reduced_stderr_per_mm == Approx(mus_spread).epsilon(0.02));
    CHECK_FALSE(inverter.invert({std::nullopt, measured.m_r, measured.m_t, std::nullopt, s, "x"}, {}).mu_a_stderr_per_mm.has_value());
}
