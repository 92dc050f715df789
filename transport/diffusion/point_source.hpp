#pragma once
// The building block of the dipole and multipole models: the diffuse flux leaving a flat boundary due to an
// isotropic point source of unit power in an infinite medium, seen from the boundary at signed distance w
// (positive on the medium's side) and lateral distance r (Farrell, Patterson & Wilson 1992; Jensen et al. 2001 Eq. 4
// and Donner & Jensen 2005 Eq. 12-13 are sums of this term):
//   E(r) = w (1 + sigma_tr rho) exp(-sigma_tr rho) / (4 pi rho^3),  rho = sqrt(r^2 + w^2).
// Its 2-D Fourier (Hankel) transform, 2 pi int E(r) J0(k r) r dr, is sgn(w) exp(-|w| s) / 2 with
// s = sqrt(sigma_tr^2 + k^2): E = -d/dw [exp(-sigma_tr rho) / (4 pi rho)], and the transform of
// exp(-sigma_tr rho) / (4 pi rho) is exp(-|w| s) / (2 s) (Weyl's identity). At k = 0 this is the analytic
// integral over the plane, sgn(w) exp(-sigma_tr |w|) / 2.
#include <cmath>
#include <numbers>

namespace skinspec::diffusion {

inline double point_source_exitance(double w, double r, double sigma_tr) {
    if (w == 0.0) return 0.0;  // a source on the boundary sends nothing through it at r > 0
    const double rho2 = r * r + w * w;
    const double rho = std::sqrt(rho2);
    return w * (1.0 + sigma_tr * rho) * std::exp(-sigma_tr * rho) / (4.0 * std::numbers::pi * rho2 * rho);
}

inline double point_source_transform(double w, double s) {
    if (w == 0.0) return 0.0;
    return std::copysign(0.5 * std::exp(-std::abs(w) * s), w);
}

}  // namespace skinspec::diffusion
