#include "inverse/iad/integrating_sphere.hpp"

#include <algorithm>

namespace skinspec {
namespace {

struct Sphere {
    SpherePorts ports;
    double wall, detector;
    bool baffle;
    double gain(double sample_reflectance, double third_reflectance) const {
        return sphere_gain(ports, wall, detector, baffle, sample_reflectance, third_reflectance);
    }
};

Sphere reflection_sphere(const SlabSetup& s) { return {s.r_ports(), s.r_wall, s.r_detector, s.r_baffle != 0.0}; }
Sphere transmission_sphere(const SlabSetup& s) { return {s.t_ports(), s.t_wall, s.t_detector, s.t_baffle != 0.0}; }

// One sphere, reflection (iad manual, "Reflectance measurement for one sphere"): the scattered reflection and the part
// of the beam hitting the wall first reach the detector after a first bounce r_first = r_w (1 - a_t) behind a baffle
// (1 without), the collected unscattered reflection after one bounce on the wall; the sphere multiplies both by its
// gain. M_R = r_std (P - P_0) / (P_std - P_0), the standard and the empty port measured the same way.
double one_sphere_r(const SlabReflectances& slab, const SlabSetup& s) {
    const auto sphere = reflection_sphere(s);
    const double f = s.wall_first, rw = s.r_wall;
    const double r_first = sphere.baffle ? rw * (1.0 - sphere.ports.third) : 1.0;
    const double scattered = std::max(0.0, slab.ur1 - slab.ru);
    const double p = sphere.gain(slab.uru, 0.0) * (r_first * ((1.0 - f) * scattered + f * rw) + rw * (1.0 - f) * s.r_unscattered_collected * slab.ru);
    const double p_std = sphere.gain(s.r_standard, 0.0) * r_first * ((1.0 - f) * s.r_standard + f * rw);
    const double p_0 = sphere.gain(0.0, 0.0) * r_first * f * rw;
    return s.r_standard * (p - p_0) / (p_std - p_0);
}

// One sphere, transmission (iad manual, "Transmittance measurement for one sphere"): the third port holds the
// standard (or matches the wall when it has no area, or is open when no unscattered light is collected); the 100 %
// measurement puts the beam on it through the empty sample port: M_T = [r_first (UT1 - T_u) + r_t f_u T_u]
// G(URU, r_t) / G(0, r_cal).
double one_sphere_t(const SlabReflectances& slab, const SlabSetup& s) {
    const auto sphere = transmission_sphere(s);
    const double at = sphere.ports.third;
    double r_cal = s.t_standard, r_third = s.t_standard;
    if (at == 0.0) r_cal = r_third = s.t_wall;
    else if (s.t_unscattered_collected == 0.0) r_third = 0.0;
    const double r_first = sphere.baffle ? s.t_wall * (1.0 - at) + r_third * at : 1.0;
    const double scattered = std::max(0.0, slab.ut1 - slab.tu);
    return (r_first * scattered + r_third * s.t_unscattered_collected * slab.tu) * sphere.gain(slab.uru, r_third) / sphere.gain(0.0, r_cal);
}

// Two spheres (Pickering et al. 1993; iadpython docs, Gain_11, Two_Sphere_R, Two_Sphere_T): light that crosses the
// sample into the other sphere comes back, G_11 = G / (1 - a_s a_s' r_w r_w' (1 - a_t)(1 - a_t') G G' UTU^2).
struct TwoSpheres {
    Sphere r, t;
    double f;
    double loop(double uru, double utu) const {
        return 1.0 - r.ports.sample * t.ports.sample * r.wall * t.wall * (1.0 - r.ports.third) * (1.0 - t.ports.third) * r.gain(uru, 0.0) *
                         t.gain(uru, 0.0) * utu * utu;
    }
    double detector_r(double ur1, double uru, double ut1, double utu) const {
        const double g11 = r.gain(uru, 0.0) / loop(uru, utu);
        return r.ports.detector * (1.0 - r.ports.third) * r.wall * g11 *
               ((1.0 - f) * ur1 + f * r.wall + (1.0 - f) * t.ports.sample * (1.0 - t.ports.third) * t.wall * ut1 * utu * t.gain(uru, 0.0));
    }
    double detector_t(double ur1, double uru, double ut1, double utu) const {
        const double g22 = t.gain(uru, 0.0) / loop(uru, utu);
        return t.ports.detector * (1.0 - t.ports.third) * t.wall * g22 *
               ((1.0 - f) * ut1 + (1.0 - r.ports.third) * r.wall * r.ports.sample * utu * (f * r.wall + (1.0 - f) * ur1) * r.gain(uru, 0.0));
    }
};

}  // namespace

double sphere_gain(const SpherePorts& ports, double wall, double detector, bool baffle, double sample_reflectance, double third_reflectance) {
    if (baffle) {
        const double wall_prime = wall + (ports.third / ports.wall) * third_reflectance;
        return 1.0 / (1.0 - wall_prime * (ports.wall + (1.0 - ports.third) * (ports.detector * detector + ports.sample * sample_reflectance)));
    }
    return 1.0 / (1.0 - ports.wall * wall - ports.detector * detector - ports.sample * sample_reflectance - ports.third * third_reflectance);
}

PredictedMeasurement predicted_measurement(const SlabReflectances& slab, const SlabSetup& s) {
    // The collected part of the unscattered light (iad manual, "Integrating-sphere corrections").
    const double ur1 = slab.ur1 - (1.0 - s.r_unscattered_collected) * slab.ru;
    const double ut1 = slab.ut1 - (1.0 - s.t_unscattered_collected) * slab.tu;
    if (s.spheres == 0.0) return {ur1, ut1};
    if (s.spheres == 1.0) return {one_sphere_r(slab, s), one_sphere_t(slab, s)};
    const TwoSpheres two{reflection_sphere(s), transmission_sphere(s), s.wall_first};
    const double r_0 = two.detector_r(0.0, 0.0, 0.0, 0.0), t_0 = two.detector_t(0.0, 0.0, 0.0, 0.0);
    const double m_r = s.r_standard * (two.detector_r(ur1, slab.uru, ut1, slab.utu) - r_0) /
                       (two.detector_r(s.r_standard, s.r_standard, 0.0, 0.0) - r_0);
    const double m_t = (two.detector_t(ur1, slab.uru, ut1, slab.utu) - t_0) / (two.detector_t(0.0, 0.0, 1.0, 1.0) - t_0);
    return {m_r, m_t};
}

}  // namespace skinspec
