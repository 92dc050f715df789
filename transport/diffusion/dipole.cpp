#include "transport/diffusion/dipole.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "transport/diffusion/point_source.hpp"
#include "transport/fresnel.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

double diffuse_fresnel_reflectance(double eta) {
    // The fits hold within 0.005 of the exact hemispherical average of the Fresnel reflectance for eta in
    // [0.4, 2.5]; beyond, they drift and pass 1 near eta = 3.8 (found by the stress grid: R_d > 1 at eta = 4).
    if (!(eta >= min_fitted_relative_index && eta <= max_fitted_relative_index)) {
        throw InputError("relative index of refraction eta = " + format_number(eta) + " is outside [" + format_number(min_fitted_relative_index) + ", " +
                         format_number(max_fitted_relative_index) + "], where the diffuse Fresnel reflectance fits of the diffusion models hold");
    }
    if (eta >= 1.0) return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    return -0.4399 + 0.7099 / eta - 0.3319 / (eta * eta) + 0.0636 / (eta * eta * eta);
}

Dipole::Dipole(const DipoleMedium& m) : medium_(m) {
    const auto check = [](bool ok, const char* field, double v, const char* range) {
        if (!ok) throw InputError(std::string("dipole: ") + field + " = " + format_number(v) + " is outside " + range);
    };
    check(std::isfinite(m.reduced_scattering) && m.reduced_scattering >= 0.0, "reduced scattering", m.reduced_scattering, "[0, inf)");
    check(std::isfinite(m.absorption) && m.absorption >= 0.0, "absorption", m.absorption, "[0, inf)");
    check(m.reduced_scattering + m.absorption > 0.0, "sigma_t'", m.reduced_scattering + m.absorption, "(0, inf)");
    check(m.g > -1.0 && m.g < 1.0, "g", m.g, "(-1, 1)");
    const double sigma_t = m.reduced_scattering + m.absorption;
    alpha_prime_ = m.reduced_scattering / sigma_t;
    sigma_tr_ = std::sqrt(3.0 * m.absorption * sigma_t);
    const double f_dr = diffuse_fresnel_reflectance(m.eta);
    a_ = (1.0 + f_dr) / (1.0 - f_dr);
    z_r_ = 1.0 / sigma_t;
    z_v_ = z_r_ * (1.0 + 4.0 * a_ / 3.0);
}

double Dipole::radial_reflectance(double r) const {
    // Eq. 4: R_d(r) = alpha'/(4 pi) [z_r (sigma_tr d_r + 1) e^{-sigma_tr d_r} / d_r^3 + z_v (sigma_tr d_v + 1) e^{-sigma_tr d_v} / d_v^3].
    return alpha_prime_ * (diffusion::point_source_exitance(z_r_, r, sigma_tr_) + diffusion::point_source_exitance(z_v_, r, sigma_tr_));
}

double Dipole::total_reflectance() const {
    const double s = std::sqrt(3.0 * (1.0 - alpha_prime_));
    return 0.5 * alpha_prime_ * (1.0 + std::exp(-4.0 / 3.0 * a_ * s)) * std::exp(-s);
}

double Dipole::single_scattering_brdf(double cos_in, double cos_out, double azimuth_deg) const {
    const auto refracted_sine = [&](double mu) { return std::sqrt(std::max(0.0, 1.0 - mu * mu)) / medium_.eta; };
    const double s_i = refracted_sine(cos_in), s_o = refracted_sine(cos_out);
    if (s_i >= 1.0 || s_o >= 1.0) return 0.0;  // no refracted ray (eta < 1 beyond the critical angle)
    const double mu_i = std::sqrt(1.0 - s_i * s_i), mu_o = std::sqrt(1.0 - s_o * s_o);
    // Light travels down along (-s_i, 0, -mu_i); the outgoing ray leaves along (s_o cos phi, s_o sin phi, mu_o),
    // phi measured from the direction towards the light.
    const double phi = azimuth_deg * std::numbers::pi / 180.0;
    const double cos_scatter = -s_i * s_o * std::cos(phi) - mu_i * mu_o;
    const double g = medium_.g;
    const double phase = (1.0 - g * g) / (4.0 * std::numbers::pi * std::pow(1.0 + g * g - 2.0 * g * cos_scatter, 1.5));
    const double sigma_s = medium_.reduced_scattering / (1.0 - g);
    const double albedo = sigma_s / (sigma_s + medium_.absorption);
    const double t_in = 1.0 - fresnel_reflectance(cos_in, 1.0, medium_.eta);
    const double t_out = 1.0 - fresnel_reflectance(cos_out, 1.0, medium_.eta);
    return albedo * t_in * t_out * phase / (mu_i + mu_o);
}

double Dipole::brdf(double cos_in, double cos_out) const {
    // Fresnel transmittance F_t = 1 - F_r entering/leaving the medium of relative index eta.
    const double t_in = 1.0 - fresnel_reflectance(cos_in, 1.0, medium_.eta);
    const double t_out = 1.0 - fresnel_reflectance(cos_out, 1.0, medium_.eta);
    return t_in * t_out * total_reflectance() / std::numbers::pi;
}

}  // namespace skinspec
