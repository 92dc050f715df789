#pragma once
// Radial diffuse reflectance and transmittance profiles of a material in a diffusion mode, per wavelength
// (layered materials) or per band (homogeneous materials): what `skinspec profile` writes and what lit
// swatches convolve with the illumination. Per unit incident power (entry transmittance included), per mm^2.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "transport/diffusion/diffusion_model.hpp"
#include "spectral/wavelength_grid.hpp"

namespace skinspec {

struct ChannelProfile {
    std::string label;                      // "550 nm" or the band name
    double wavelength_nm = 0.0;             // 0 for bands
    std::vector<double> reflectance_per_mm2;
    std::vector<double> transmittance_per_mm2;  // empty unless asked for
    double total_reflectance = 0.0;         // diffuse, analytic: 2 pi int R(r) r dr
    double total_transmittance = 0.0;
    double specular_reflectance = 0.0;
    // Monte Carlo profiles (the volumetric walk): standard errors per radius; empty for deterministic ones.
    std::vector<double> reflectance_stderr_per_mm2;
    std::vector<double> transmittance_stderr_per_mm2;
    std::uint64_t rays = 0;             // photons traced (0: deterministic)
    // The largest standard error of the diffuse reflectance (or transmittance) leaving within one of the radii a
    // Monte Carlo profile's precision covers (transport/rte/rte_profiles.hpp), and whether its target was met.
    double within_radius_stderr = 0.0;
    bool converged = true;
};

struct SpectralProfiles {
    std::string material;
    std::string model;
    std::vector<double> radii_mm;
    std::vector<ChannelProfile> channels;
    std::vector<ResultWarning> warnings;
    std::size_t max_pairs = 0;    // dipole pairs the multipole sums needed
    std::size_t frequencies = 0;  // samples of the layered inverse transform (0 for one slab)
    bool converged = true;
    bool partial = false;  // stopped: the channels finished so far
    std::optional<double> stderr_target;  // Monte Carlo profiles run to a precision target: the target
};

// The channels profiles of `material` have: one per wavelength of `wavelengths` for a layered material, one per band
// for a homogeneous one.
std::size_t profile_channel_count(const Material& material, const WavelengthGrid& wavelengths);

// `wavelengths` is used for layered materials and ignored for homogeneous ones (all their bands).
// InputError for radii that are negative, non-finite or not increasing.
// `cancel`: checked between channels and within a transform; a stop leaves the channels finished so far, partial.
// `on_progress`: after each channel.
SpectralProfiles diffusion_profiles(const Material& material, const WavelengthGrid& wavelengths, std::span<const double> radii_mm,
                                    const DiffusionOptions& options, bool transmittance, const std::atomic<bool>* cancel = nullptr,
                                    const std::function<void(const Progress&)>& on_progress = {});

}  // namespace skinspec
