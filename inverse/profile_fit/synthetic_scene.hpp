#pragma once
// A synthetic planar scene for the round trip of Mukaigawa et al. 2009 Sec. 4.1: a non-uniformly lit flat sample rendered
// with the dipole (Eq. 10 with the exact, unquantised profile), optionally with multiplicative Gaussian noise.
#include <cstdint>

#include "transport/diffusion/dipole.hpp"
#include "inverse/profile_fit/profile_system.hpp"

namespace skinspec {

struct SyntheticSceneSpec {
    int width = 64;
    int height = 64;
    double pitch_mm = 0.05;
    DipoleMedium medium{2.19, 0.002, 1.3};  // the paper's ground truth (per mm)
    double noise = 0.0;                     // relative standard deviation of the observed values
    std::uint64_t seed = 1;
};

// Irradiance: a bright off-centre Gaussian spot, a weaker second spot and a linear ramp over a 10 % floor,
// times the pixel area (c = power per pixel).
PlanarScene synthetic_planar_scene(const SyntheticSceneSpec& spec);

}  // namespace skinspec
