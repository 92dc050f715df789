#pragma once
// Directions as unit vectors in the frame of a plane-parallel slab: z is the inward normal (into the skin,
// downward), so z > 0 travels down and z < 0 travels up.
#include <cmath>

#include <glm/vec3.hpp>

namespace skinspec {

using Direction = glm::dvec3;

// `d` turned by the polar angle theta (given as cos and sin) at azimuth phi about itself
// (Witt 1977 / MCML's SpinTheta, Wang, Jacques & Zheng 1995 Eq. 3.24-3.26).
inline Direction deflect(const Direction& d, double cos_theta, double sin_theta, double phi) {
    const double cos_phi = std::cos(phi);
    const double sin_phi = std::sin(phi);
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
