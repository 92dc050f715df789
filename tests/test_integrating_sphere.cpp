#include <catch2/catch.hpp>

#include <array>

#include "inverse/iad/integrating_sphere.hpp"
#include "inverse/iad/inverse_adding_doubling.hpp"

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

namespace {

// One forward calculation of Prahl's iad 4-0-0 (`iad -z -M 0 -q 32 ...`, built outside the repository from
// github.com/scottprahl/iad; docs/IAD.md): the slab (a, b, g, n, slides), the spheres and what iad printed.
struct IadForward {
    const char* command;  // the options given to iad, for the failure message
    SlabOptics optics;
    double sample_index, slide_index, slide_thickness_mm;
    double spheres, baffle;
    std::array<double, 5> r_sphere;  // -1 'd_sphere d_sample d_entrance d_detector r_wall'
    std::array<double, 5> t_sphere;  // -2 'd_sphere d_sample d_third d_detector r_wall'
    double wall_first, r_unscattered_collected, t_unscattered_collected, r_standard;
    double m_r, m_t;  // iad's M_R (sphere), M_T (sphere); with -S 0 its R total, T total
};

SlabSetup setup_of(const IadForward& c) {
    SlabSetup s;
    s.sample_index = c.sample_index;
    s.slide_index = c.slide_index;
    s.slide_thickness_mm = c.slide_thickness_mm;
    s.g = c.optics.g;
    s.spheres = c.spheres;
    s.r_baffle = s.t_baffle = c.baffle;
    s.r_sphere_mm = c.r_sphere[0], s.r_sample_port_mm = c.r_sphere[1], s.r_entrance_port_mm = c.r_sphere[2];
    s.r_detector_port_mm = c.r_sphere[3], s.r_wall = c.r_sphere[4];
    s.t_sphere_mm = c.t_sphere[0], s.t_sample_port_mm = c.t_sphere[1], s.t_third_port_mm = c.t_sphere[2];
    s.t_detector_port_mm = c.t_sphere[3], s.t_wall = c.t_sphere[4];
    s.wall_first = c.wall_first;
    s.r_unscattered_collected = c.r_unscattered_collected;
    s.t_unscattered_collected = c.t_unscattered_collected;
    s.r_standard = s.t_standard = c.r_standard;  // iad's -R sets the standard of both spheres
    return s;
}

}  // namespace

TEST_CASE("the sphere corrections match Prahl's iad forward calculation (one and two spheres without baffles)", "[iad]") {
    // iad prints four decimals (half a unit: 5e-5) and differs from skinspec's 24-channel adding-doubling by up to 1e-4
    // in R and T (docs/IAD.md): 1.5e-4 in all. Where iad's code differs from its manual skinspec follows the manual
    // (docs/IAD.md): baffled spheres are not compared, and two spheres' M_T gets 6e-4, since iad's G_11 has a_w a_w'
    // where the manual has r_w r_w' (with iad's product the two-sphere M_T below match to 1.5e-4 as well).
    const std::array<double, 5> s200{200, 25, 12.7, 1, 0.96}, s200w{200, 25, 12.7, 1, 0.99};
    const std::array<double, 5> s150{150, 20, 10, 2, 0.98}, s100{100, 15, 8, 3, 0.95};
    const IadForward cases[] = {
        {"-S 0 -a 0.9 -b 1 -g 0 -n 1.4 -N 1.5 -D 1", {0.9, 1, 0}, 1.4, 1.5, 1, 0, 0, s200, s200, 0, 1, 1, 1, 0.2352, 0.5153},
        {"-H 0 -S 1 -a 0.9 -b 1 -g 0 -n 1.4 -N 1.5 -D 1 -1 '200 25 12.7 1 0.96' -2 (same)", {0.9, 1, 0}, 1.4, 1.5, 1, 1, 0, s200, s200, 0, 1, 1, 1, 0.2186, 0.5292},
        {"-H 0 -S 1 -a 0.99 -b 4 -g 0.8 -n 1.33 -1 '150 20 10 2 0.98' -2 '100 15 8 3 0.95'", {0.99, 4, 0.8}, 1.33, 1.0, 0, 1, 0, s150, s100, 0, 1, 1, 1, 0.2407, 0.6327},
        {"-H 0 -S 1 -f 0.5 -a 0.8 -b 2 -g 0.5 -n 1.4 -1 '200 25 12.7 1 0.96' -2 (same)", {0.8, 2, 0.5}, 1.4, 1.0, 0, 1, 0, s200, s200, 0.5, 1, 1, 1, 0.1047, 0.3260},
        {"-H 0 -S 2 -f 0.5 -a 0.8 -b 2 -g 0.5 -n 1.4 -1 '200 25 12.7 1 0.96' -2 (same)", {0.8, 2, 0.5}, 1.4, 1.0, 0, 2, 0, s200, s200, 0.5, 1, 1, 1, 0.1120, 0.3211},
        {"-H 0 -S 1 -c 0 -C 0 -a 0.9 -b 0.5 -g 0 -n 1.5 -1 '200 25 12.7 1 0.96' -2 (same)", {0.9, 0.5, 0}, 1.5, 1.0, 0, 1, 0, s200, s200, 0, 0, 0, 1, 0.1132, 0.1196},
        {"-H 0 -S 1 -R 0.98 -a 0.95 -b 3 -g 0.9 -n 1.4 -1 '200 25 12.7 1 0.99' -2 (same)", {0.95, 3, 0.9}, 1.4, 1.0, 0, 1, 0, s200w, s200w, 0, 1, 1, 0.98, 0.0783, 0.6708},
        {"-H 0 -S 2 -a 0.9 -b 1 -g 0 -n 1.4 -N 1.5 -D 1 -1 '200 25 12.7 1 0.96' -2 (same)", {0.9, 1, 0}, 1.4, 1.5, 1, 2, 0, s200, s200, 0, 1, 1, 1, 0.2392, 0.5349},
        {"-H 0 -S 2 -a 0.99 -b 4 -g 0.8 -n 1.33 -1 '150 20 10 2 0.98' -2 '100 15 8 3 0.95'", {0.99, 4, 0.8}, 1.33, 1.0, 0, 2, 0, s150, s100, 0, 1, 1, 1, 0.2700, 0.6516},
    };
    SlabInverter inverter(IadSettings{});
    for (const auto& c : cases) {
        const auto m = inverter.predict(c.optics, setup_of(c));
        INFO("iad -z -M 0 -q 32 " << c.command);
        CHECK(m.m_r == Approx(c.m_r).margin(1.5e-4));
        CHECK(m.m_t == Approx(c.m_t).margin(c.spheres == 2.0 ? 6e-4 : 1.5e-4));
    }
}
