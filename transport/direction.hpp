#pragma once
// Directions as unit vectors in the frame of a plane-parallel slab: z is the inward normal (into the skin,
// downward), so z > 0 travels down and z < 0 travels up.
#include <cmath>

#include <glm/vec3.hpp>

namespace skinspec {

using Direction = glm::dvec3;

// A uniformly distributed azimuth as (cos phi, sin phi), by rejection from the unit disk (von Neumann 1951,
// "Various techniques used in connection with random digits"): no trigonometric call.
struct Azimuth {
    double cos_phi;
    double sin_phi;
};

template <class Random>
Azimuth sample_azimuth(Random& random) {
    while (true) {
        const double x = 2.0 * random.uniform() - 1.0;
        const double y = 2.0 * random.uniform() - 1.0;
        const double r2 = x * x + y * y;
        if (r2 <= 1.0 && r2 > 1e-12) {
            const double inv = 1.0 / std::sqrt(r2);
            return {x * inv, y * inv};
        }
    }
}

// `d` turned by the polar angle theta (given as cos and sin) at azimuth phi about itself
// (Witt 1977 / MCML's SpinTheta, Wang, Jacques & Zheng 1995 Eq. 3.24-3.26).
inline Direction deflect(const Direction& d, double cos_theta, double sin_theta, Azimuth azimuth) {
    const double cos_phi = azimuth.cos_phi;
    const double sin_phi = azimuth.sin_phi;
    if (std::abs(d.z) > 0.99999) {
        const double sign = d.z >= 0.0 ? 1.0 : -1.0;
        return {sin_theta * cos_phi, sin_theta * sin_phi, sign * cos_theta};
    }
    const double t = std::sqrt(1.0 - d.z * d.z);
    return {sin_theta * (d.x * d.z * cos_phi - d.y * sin_phi) / t + d.x * cos_theta,
            sin_theta * (d.y * d.z * cos_phi + d.x * sin_phi) / t + d.y * cos_theta,
            -sin_theta * cos_phi * t + d.z * cos_theta};
}

}  // namespace skinspec
