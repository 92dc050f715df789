#pragma once
// Fresnel reflectance and Snell refraction at a planar interface normal to z (Born & Wolf, Principles of
// Optics, Sec. 1.5.2, Eq. 21 for the amplitude coefficients; unpolarised R = (rs^2 + rp^2) / 2).
#include <optional>

#include "transport/direction.hpp"

namespace skinspec {

// Unpolarised reflectance for a ray meeting the interface with |cos theta_i| = cos_incident, going from
// index n_from into n_to; 1 under total internal reflection, 0 for matched indices.
double fresnel_reflectance(double cos_incident, double n_from, double n_to);

// Snell refraction of `d` through the interface (keeps the sign of d.z); nullopt under total internal reflection.
std::optional<Direction> refract(const Direction& d, double n_from, double n_to);

// Mirror reflection about the interface.
inline Direction mirror(const Direction& d) { return {d.x, d.y, -d.z}; }

}  // namespace skinspec
