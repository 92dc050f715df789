#include "transport/diffusion/rough_surface.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "transport/fresnel.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {
constexpr int half_vector_steps = 128;  // Beckmann CDF steps
constexpr int azimuth_steps = 64;       // over [0, pi]; the integrand is symmetric in azimuth
constexpr int incidence_steps = 64;     // cosine-weighted incident directions for rho_d
}  // namespace

RoughSurface::RoughSurface(double m, double n_outside, double n_inside) : m_(m), n_out_(n_outside), n_in_(n_inside) {
    if (!(m > 0.0 && m <= 2.0)) throw InputError("rough surface: roughness = " + format_number(m) + " is outside (0, 2]");
    for (const double n : {n_outside, n_inside}) {
        if (!(n >= 1.0 && n <= 5.0)) throw InputError("rough surface: refractive index = " + format_number(n) + " is outside [1, 5]");
    }
    // rho_d = 2 int rho(mu) mu dmu = int rho(sqrt(v)) dv: midpoint rule in v = mu^2.
    double sum = 0.0;
    for (int j = 0; j < incidence_steps; ++j) sum += directional_albedo(std::sqrt((j + 0.5) / incidence_steps), true);
    rho_d_ = sum / incidence_steps;
}

double RoughSurface::directional_albedo(double cos_incident, bool from_inside) const {
    // Eq. 23: f_r = D G F / (4 (n.i)(n.o)). With the half vector h drawn from D(h) (n.h) and o the mirror of i
    // about h (d omega_o = 4 (o.h) d omega_h), int f_r (n.o) d omega_o = E_h[G F (i.h) / ((n.i)(n.h))].
    const double mu_i = std::clamp(cos_incident, 1e-9, 1.0);
    const double sin_i = std::sqrt(1.0 - mu_i * mu_i);
    const double n_from = from_inside ? n_in_ : n_out_;
    const double n_to = from_inside ? n_out_ : n_in_;
    double sum = 0.0;
    for (int a = 0; a < half_vector_steps; ++a) {
        // Beckmann: P(tan^2 theta_h < t) = 1 - exp(-t / m^2).
        const double tan2 = -m_ * m_ * std::log1p(-(a + 0.5) / half_vector_steps);
        const double cos_h = 1.0 / std::sqrt(1.0 + tan2);
        const double sin_h = std::sqrt(1.0 - cos_h * cos_h);
        for (int b = 0; b < azimuth_steps; ++b) {
            const double phi = std::numbers::pi * (b + 0.5) / azimuth_steps;
            const double hx = sin_h * std::cos(phi), hz = cos_h;
            const double i_dot_h = sin_i * hx + mu_i * hz;  // i = (sin_i, 0, mu_i) points away from the surface
            if (i_dot_h <= 0.0) continue;
            const double mu_o = 2.0 * i_dot_h * hz - mu_i;  // o = 2 (i.h) h - i
            if (mu_o <= 0.0) continue;
            // V-cavity shadowing and masking (Torrance & Sparrow 1967).
            const double g = std::min({1.0, 2.0 * hz * mu_o / i_dot_h, 2.0 * hz * mu_i / i_dot_h});
            sum += g * fresnel_reflectance(i_dot_h, n_from, n_to) * i_dot_h / (mu_i * hz);
        }
    }
    return sum / (half_vector_steps * azimuth_steps);
}

double RoughSurface::entry_transmittance(double cos_incident) const { return 1.0 - directional_albedo(cos_incident, false); }

}  // namespace skinspec
