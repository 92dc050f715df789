#pragma once
// The forward problem of inverse adding-doubling: a homogeneous slab of albedo a, optical thickness b and
// Henyey-Greenstein anisotropy g, between optional clear slides, in air. What the sphere formulas need (van de
// Hulst 1980's names, as in Prahl et al. 1993, Appl. Opt. 32:559, and the iad manual): the total reflection and
// transmission for the collimated beam (UR1, UT1) and for diffuse light (URU, UTU), and their unscattered parts
// (R_u, T_u). Adding-doubling (transport/adding_doubling) solves the slab; the unscattered parts are closed form.
#include <cstddef>

#include "inverse/iad/slab_measurement.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"

namespace skinspec {

struct SlabOptics {
    double albedo = 0.0;             // a = mu_s / (mu_a + mu_s)
    double optical_thickness = 0.0;  // b = (mu_a + mu_s) d
    double g = 0.0;
};

struct SlabReflectances {
    double ur1 = 0.0, ut1 = 0.0;  // collimated incidence: everything leaving the top / the bottom
    double uru = 0.0, utu = 0.0;  // diffuse incidence
    double ru = 0.0, tu = 0.0;    // the unscattered parts of UR1 and UT1
};

// `channels`: the adding-doubling quadrature (AdOptions::channels). The cache carries the redistribution matrices
// across calls with the same g (an inversion's evaluations).
SlabReflectances slab_reflectances(const SlabOptics& optics, const SlabSetup& setup, std::size_t channels, AdCache& cache);

// The unscattered reflection and transmission of the beam alone (closed form: Fresnel at every face, incoherent
// multiple reflections in the slides and the sample, Beer-Lambert along the refracted path; Prahl et al. 1993).
struct Unscattered {
    double r = 0.0, t = 0.0;
};
Unscattered unscattered(double optical_thickness, const SlabSetup& setup);

}  // namespace skinspec
