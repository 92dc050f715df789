#pragma once
// The dipole diffusion approximation of Jensen, Marschner, Levoy & Hanrahan 2001 for a
// semi-infinite homogeneous medium: radial diffuse reflectance R_d(r) (Eq. 4), total diffuse reflectance
// (Sec. 2.4), the BRDF approximation (Sec. 2.4) and the single-scattering term (Eq. 3 with Hanrahan &
// Krueger's BRDF). Lengths in any one unit: coefficients per unit, radii in the unit (mm for Jensen's table).
namespace skinspec {

// Diffuse Fresnel reflectance of the boundary for relative index eta = n_inside / n_outside:
// eta >= 1 Jensen et al. 2001 (Egan & Hilgeman): -1.440/eta^2 + 0.710/eta + 0.668 + 0.0636 eta;
// eta < 1 Donner & Jensen 2005: -0.4399 + 0.7099/eta - 0.3319/eta^2 + 0.0636/eta^3.
// InputError for eta outside [0.4, 2.5], where the fits stay within 0.005 of the exact average.
constexpr double min_fitted_relative_index = 0.4;
constexpr double max_fitted_relative_index = 2.5;
double diffuse_fresnel_reflectance(double eta);

struct DipoleMedium {
    double reduced_scattering = 0.0;  // sigma_s' per unit length
    double absorption = 0.0;          // sigma_a per unit length
    double eta = 1.3;                 // relative index of refraction
    double g = 0.0;                   // Henyey-Greenstein asymmetry for the single-scattering term (sigma_s = sigma_s' / (1 - g))
};

class Dipole {
public:
    // InputError for negative or non-finite coefficients, sigma_t' = 0, or eta outside [0.4, 2.5].
    explicit Dipole(const DipoleMedium& medium);

    double reduced_albedo() const { return alpha_prime_; }
    double effective_transport() const { return sigma_tr_; }  // sigma_tr = sqrt(3 sigma_a sigma_t')
    double real_source_depth() const { return z_r_; }         // z_r = 1 / sigma_t'
    double virtual_source_height() const { return z_v_; }     // z_v = z_r (1 + 4A/3)
    double boundary_a() const { return a_; }                  // A = (1 + F_dr) / (1 - F_dr)

    // Eq. 4: R_d(r) per unit area.
    double radial_reflectance(double r) const;
    // Sec. 2.4: R_d = (alpha'/2) (1 + exp(-(4/3) A sqrt(3 (1 - alpha')))) exp(-sqrt(3 (1 - alpha'))).
    double total_reflectance() const;
    // Sec. 2.2 single scattering for a flat, uniformly lit surface (Hanrahan & Krueger's BRDF, the integral of
    // Eq. 6 over the surface): f1 = alpha F_t(theta_i) F_t(theta_o) p(cos) / (mu_i' + mu_o') per sr, with
    // mu' the refracted cosines, alpha = sigma_s / sigma_t, p Henyey-Greenstein with g, and cos the cosine
    // between the refracted incident and outgoing directions; azimuth_deg is the azimuth between the
    // directions to the light and to the viewer (180 deg: the mirror direction).
    double single_scattering_brdf(double cos_in, double cos_out, double azimuth_deg) const;
    // Sec. 2.4 diffuse part of the BRDF approximation: F_t(eta, theta_i) F_t(eta, theta_o) R_d / pi (per sr).
    double brdf(double cos_in, double cos_out) const;
    // Sec. 2.4 BRDF approximation: single scattering plus the diffuse part.
    double brdf(double cos_in, double cos_out, double azimuth_deg) const {
        return single_scattering_brdf(cos_in, cos_out, azimuth_deg) + brdf(cos_in, cos_out);
    }

private:
    DipoleMedium medium_;
    double alpha_prime_, sigma_tr_, z_r_, z_v_, a_;
};

}  // namespace skinspec
