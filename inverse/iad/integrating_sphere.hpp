#pragma once
// What an integrating-sphere experiment reports for a slab: the normalised measurements M_R and M_T predicted from
// the slab's reflections (inverse/iad/slab_reflectances.hpp) and the setup (inverse/iad/slab_measurement.hpp).
// Substitution measurements with no sphere, one sphere (R and T measured one after the other in the same kind of
// sphere) or two spheres (R and T at once, light passing between them through the sample). The formulas are those
// of Pickering et al. 1993 (Appl. Opt. 32:399) as written in Prahl's iad manual ("Integrating-sphere corrections")
// and the iadpython documentation (sphere gain, Gain_11, Two_Sphere_R/T); iad's lost-light Monte Carlo is not
// modelled (samples wider than the ports: docs/IAD.md).
#include "inverse/iad/slab_measurement.hpp"
#include "inverse/iad/slab_reflectances.hpp"

namespace skinspec {

struct PredictedMeasurement {
    double m_r = 0.0;
    double m_t = 0.0;
};

// The sphere's gain for diffuse light: its power on the walls over the power that started it, for a sample of diffuse
// reflectance `sample_reflectance` in the sample port and `third_reflectance` in the third port (iad manual,
// "Gain"): 1 / (1 - a_w r_w - a_d r_d - a_s r_s - a_t r_t) without a baffle, and with one (light from the sample
// reaches the detector only after a bounce) 1 / (1 - a_w r_w' - r_w' (1 - a_t)(a_d r_d + a_s r_s)), r_w' = r_w + (a_t / a_w) r_t.
double sphere_gain(const SpherePorts& ports, double wall, double detector, bool baffle, double sample_reflectance, double third_reflectance);

PredictedMeasurement predicted_measurement(const SlabReflectances& slab, const SlabSetup& setup);

}  // namespace skinspec
