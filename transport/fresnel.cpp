#include "transport/fresnel.hpp"

#include <cmath>

namespace skinspec {

double fresnel_reflectance(double cos_incident, double n_from, double n_to) {
    if (n_from == n_to) return 0.0;
    const double cos_i = std::min(std::abs(cos_incident), 1.0);
    const double eta = n_from / n_to;
    const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);  // Snell
    if (sin2_t >= 1.0) return 1.0;                            // total internal reflection
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (n_from * cos_i - n_to * cos_t) / (n_from * cos_i + n_to * cos_t);
    const double rp = (n_from * cos_t - n_to * cos_i) / (n_from * cos_t + n_to * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

std::optional<Direction> refract(const Direction& d, double n_from, double n_to) {
    if (n_from == n_to) return d;
    const double eta = n_from / n_to;
    const double sin2_t = eta * eta * (1.0 - d.z * d.z);
    if (sin2_t >= 1.0) return std::nullopt;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    return Direction{eta * d.x, eta * d.y, d.z >= 0.0 ? cos_t : -cos_t};
}

}  // namespace skinspec
