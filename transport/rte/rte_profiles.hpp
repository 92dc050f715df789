#pragma once
// Radial profiles R(r), T(r) of a layered material from the volumetric walk (MCML's R_r, T_r tallies; Wang,
// Jacques & Zheng 1995, Sec. 4.2: weight per ring area per incident photon), in the same type as the diffusion
// profiles (transport/diffusion/diffusion_profiles.hpp), each value with its standard error.
//
// The walk tallies rings; the value at radius r_i = i h is the mean over the ring [r_i - h/2, r_i + h/2) (the disc
// of radius h/2 at r = 0), made of two tallied half-step rings, so that every radius is the centre of its ring.
#include <cstdint>
#include <span>

#include "transport/diffusion/diffusion_profiles.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {

struct RteProfileOptions {
    std::uint64_t photons_per_wavelength = 1'000'000;
    std::uint64_t seed = 1;
    BoundaryMode boundaries = BoundaryMode::random;
    const CancelFlag* cancel = nullptr;  // a stop leaves the wavelengths finished so far (SpectralProfiles::partial)
    std::function<void(const Progress&)> on_progress;  // rays and wavelengths of the whole profile request
};

// InputError for radii that do not start at 0 with equal steps (what rings can give), fewer than two radii, or a
// layer without volumetric scattering. Totals are the walk's whole-plane diffuse R and T.
SpectralProfiles solve_rte_profiles(const LayerStack& stack, const WavelengthGrid& wavelengths, std::span<const double> radii_mm, bool transmittance,
                                    const RteProfileOptions& options);

}  // namespace skinspec
