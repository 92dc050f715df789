#pragma once
// Radial profiles R(r), T(r) of a layered material from the volumetric walk (MCML's R_r, T_r tallies; Wang,
// Jacques & Zheng 1995, Sec. 4.2: weight per ring area per incident photon), in the same type as the diffusion
// profiles (transport/diffusion/diffusion_profiles.hpp), each value with its standard error.
//
// The walk tallies rings; the value at radius r_i = i h is the mean over the ring [r_i - h/2, r_i + h/2) (the disc
// of radius h/2 at r = 0), made of two tallied half-step rings, so that every radius is the centre of its ring.
#include <cstdint>
#include <optional>
#include <span>

#include "transport/diffusion/diffusion_profiles.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {

struct RteProfileOptions {
    // Without a target: exactly this many photons per wavelength; with one: the budget.
    std::uint64_t photons_per_wavelength = 10'000'000;
    // Each wavelength runs until the standard error of the diffuse reflectance (and, with transmittance, T) leaving
    // within each of within_radii_mm() is at most this (fractions of the incident light): the precision of every share
    // of the light a kernel spreads (docs/PROFILES.md).
    std::optional<double> stderr_target;
    std::uint64_t seed = 1;
    BoundaryMode boundaries = BoundaryMode::random;
    const CancelFlag* cancel = nullptr;  // a stop leaves the wavelengths finished so far (SpectralProfiles::partial)
    std::function<void(const Progress&)> on_progress;  // rays and wavelengths of the whole profile request
};

// The radii (mm) whose enclosed reflectance a stderr target covers: 1, 2, 5 x 10^k from the profile's step up to its
// reach, and the reach (the outer edge of the last ring): log-spaced, as the radii a kernel gathers light from.
std::vector<double> within_radii_mm(std::span<const double> radii_mm);

// InputError for radii that do not start at 0 with equal steps (what rings can give), fewer than two radii, or a
// layer without volumetric scattering. Totals are the walk's whole-plane diffuse R and T.
SpectralProfiles solve_rte_profiles(const LayerStack& stack, const WavelengthGrid& wavelengths, std::span<const double> radii_mm, bool transmittance,
                                    const RteProfileOptions& options);
// Materials that differ only in absorption (their volumetric paths agree: require_shared_paths), one profile each, from
// one walk per wavelength by the exit replay (solve_rte_exit_sets): a grid of pigmentations at about one member's
// cost. One material alone is walked MCML's way (as above). The stderr target is met by every material.
std::vector<SpectralProfiles> solve_rte_profiles(const std::vector<const LayerStack*>& stacks, const WavelengthGrid& wavelengths,
                                                 std::span<const double> radii_mm, bool transmittance, const RteProfileOptions& options);
// A band material (Jensen et al. 2001's tables) per band, walked as the semi-infinite medium it stands for
// (rte_band_slab, as `spectrum --mode rte` walks it).
SpectralProfiles solve_rte_profiles(const HomogeneousMaterial& material, std::span<const double> radii_mm, bool transmittance,
                                    const RteProfileOptions& options);

}  // namespace skinspec
