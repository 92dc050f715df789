#pragma once
// A rough dielectric boundary for the diffusion models (Donner & Jensen 2005, Sec. 2.4): a
// Torrance-Sparrow microfacet BRDF (Eq. 23) with the Beckmann facet distribution of RMS slope m, the V-cavity
// shadowing term and unpolarised Fresnel reflection. Its average diffuse reflectance rho_d, seen from inside,
// replaces F_dr in A = (1 + rho_d) / (1 - rho_d) (Eq. 24); the light it does not reflect from outside,
// rho_dt (Eq. 26), replaces the Fresnel transmittance at entry and exit (Eq. 25).
//
// Both integrals are evaluated by deterministic quadrature over half-vectors drawn from the Beckmann
// distribution (midpoint rule in the distribution's CDF and in azimuth), once per surface.
namespace skinspec {

class RoughSurface {
public:
    // InputError for roughness outside (0, 2] or indices outside [1, 5].
    RoughSurface(double beckmann_roughness, double n_outside, double n_inside);

    double roughness() const { return m_; }
    double n_outside() const { return n_out_; }
    double n_inside() const { return n_in_; }
    // rho_d: cosine-weighted average over incident directions inside the medium of the reflected fraction.
    double internal_diffuse_reflectance() const { return rho_d_; }
    // rho_dt(theta) = 1 - int f_r cos: the fraction of light from outside at polar cosine mu that enters.
    double entry_transmittance(double cos_incident) const;
    // Directional albedo int f_r cos d omega for light at polar cosine mu, from outside or from inside.
    double directional_albedo(double cos_incident, bool from_inside) const;

private:
    double m_, n_out_, n_in_, rho_d_;
};

}  // namespace skinspec
