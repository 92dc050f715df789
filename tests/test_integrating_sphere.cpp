#include <catch2/catch.hpp>

#include "inverse/iad/integrating_sphere.hpp"

using namespace skinspec;

namespace {

// A slab that reflects like the diffuse standard: what a sphere reads on the standard itself.
SlabReflectances standard_like(double r_std) { return {r_std, 0.0, r_std, 0.0, 0.0, 0.0}; }

}  // namespace

TEST_CASE("sphere gain: a sphere without ports is 1 / (1 - r_w) and a black sphere gains 1", "[iad]") {
    const SpherePorts none{0.0, 0.0, 0.0, 1.0};
    CHECK(sphere_gain(none, 0.96, 0.0, false, 0.5, 0.0) == Approx(25.0));
    CHECK(sphere_gain(none, 0.96, 0.0, true, 0.5, 0.0) == Approx(25.0));
    const SpherePorts ports{0.004, 0.001, 1e-5, 1.0 - 0.00401};
    CHECK(sphere_gain(ports, 0.0, 0.0, false, 0.0, 0.0) == Approx(1.0));
}

TEST_CASE("no sphere: M_R and M_T are the slab's totals less the unscattered light not collected", "[iad]") {
    SlabSetup s;
    const SlabReflectances slab{0.3, 0.4, 0.35, 0.3, 0.05, 0.2};
    auto m = predicted_measurement(slab, s);
    CHECK(m.m_r == 0.3);
    CHECK(m.m_t == 0.4);
    s.r_unscattered_collected = 0.0;
    s.t_unscattered_collected = 0.5;
    m = predicted_measurement(slab, s);
    CHECK(m.m_r == Approx(0.25));
    CHECK(m.m_t == Approx(0.3));
}

TEST_CASE("one and two spheres: the standard reads its own reflectance, an empty port full transmission", "[iad]") {
    for (const double spheres : {1.0, 2.0}) {
        for (const double baffle : {0.0, 1.0}) {
            SlabSetup s;
            s.spheres = spheres;
            s.r_baffle = s.t_baffle = baffle;
            s.r_standard = 0.98;
            CHECK(predicted_measurement(standard_like(0.98), s).m_r == Approx(0.98).epsilon(1e-12));
            // 100 % transmission: everything through, unscattered, nothing reflected.
            const SlabReflectances open{0.0, 1.0, 0.0, 1.0, 0.0, 1.0};
            CHECK(predicted_measurement(open, s).m_t == Approx(1.0).epsilon(1e-12));
        }
    }
}

TEST_CASE("a sphere reads a darker sample relative to the standard through its gain", "[iad]") {
    // One sphere, no baffle, no unscattered light: M_R = UR1 G(URU) / G(r_std) (r_std = 1), below UR1 since G grows with
    // the sample's reflectance (iad manual, "The single reflectance sphere").
    SlabSetup s;
    s.spheres = 1.0;
    s.r_baffle = 0.0;
    const SlabReflectances slab{0.4, 0.2, 0.45, 0.2, 0.0, 0.0};
    const auto p = s.r_ports();
    const double expected = 0.4 * sphere_gain(p, s.r_wall, 0.0, false, 0.45, 0.0) / sphere_gain(p, s.r_wall, 0.0, false, 1.0, 0.0);
    CHECK(predicted_measurement(slab, s).m_r == Approx(expected).epsilon(1e-12));
    CHECK(expected < 0.4);
}
