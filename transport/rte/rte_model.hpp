#pragma once
// Plane-parallel layers for the volumetric walk (radiative transfer, MCML-class; docs/RTE.md).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "transport/phase_function.hpp"
#include "transport/spectral_request.hpp"
#include "materials/layer_stack.hpp"
#include "materials/material_file.hpp"

namespace skinspec {

struct RteLayer {
    double refractive_index = 1.0;
    double mu_a_per_cm = 0.0;
    double mu_s_per_cm = 0.0;
    double thickness_cm = 0.0;
    PhaseFunction phase;
};

struct RteStack {
    double above_refractive_index = 1.0;
    double below_refractive_index = 1.0;
    bool bottom_reflector = false;  // Lambertian reflector below the last layer (skin presets)
    std::vector<RteLayer> layers;
    double bottom_reflectance = 1.0;  // the reflector's: 1 BioSpec's ideal one, below 1 the measured hypodermis (T is what it keeps)
};

// A material's stack at one wavelength; InputError naming the first layer without volumetric scattering.
RteStack rte_stack_from(const LayerStack& stack, double wavelength_nm);

// InputError for values the walk cannot run (names the layer, field, value and range).
void validate(const RteStack& stack);

// Spatial and angular grids as in MCML (dz, dr in cm; angle bins of pi / (2 na)); 0 bins = not tallied.
struct RteGrid {
    double dz_cm = 0.01;
    double dr_cm = 0.01;
    int nz = 0;
    int nr = 0;
    int na = 0;
};

enum class BoundaryMode {
    random,  // all-or-none: reflect with probability R (MCML's default)
    split,   // outer boundaries: the transmitted part w (1 - R) escapes, the ray goes on with w R
};
std::string_view to_string(BoundaryMode mode);
BoundaryMode parse_boundary_mode(std::string_view text, std::string_view what);

struct RteRequest {
    RteStack stack;
    std::uint64_t photons = 100'000;          // the budget; exact count without a target
    std::optional<double> stderr_target;      // stop once R_diffuse's (and T's) standard error is below
    std::uint64_t seed = 1;
    double stream_key = 1.0;                  // random streams are keyed by it (the wavelength in spectra)
    double incidence_deg = 0.0;
    BoundaryMode boundaries = BoundaryMode::random;
    RteGrid grid;
    std::uint64_t max_steps_per_photon = 100'000'000;
    // Radii (cm, increasing) of the reflectance (and transmittance) leaving within each: tallied per photon, so their
    // standard errors are the photons' own spread, and a stderr target covers them beside R and T (radial profiles).
    std::vector<double> within_radii_cm;
    // White Monte Carlo (Alerstam et al. 2008): paths from mu_s alone, absorption by Beer-Lambert along them;
    // statistically the same answers as MCML's way, and the mode absorption replay uses.
    bool white = false;
    std::function<void(const Progress&)> on_progress;
    const CancelFlag* cancel = nullptr;
};

// Totals are fractions of the incident photons; arrays are in MCML's units (scaled as MCML 1.2 does):
// A_z 1/cm, A_rz 1/cm^3, R_r and T_r 1/cm^2, R_a and T_a 1/sr, R_ra and T_ra 1/(cm^2 sr). Every value
// carries its standard error.
struct RteResult {
    Estimate specular_reflectance;
    Estimate diffuse_reflectance;
    Estimate transmittance;
    Estimate absorbed;
    std::vector<Estimate> absorption_layers;
    std::vector<Estimate> absorption_z, reflectance_r, transmittance_r, reflectance_a, transmittance_a;
    std::vector<Estimate> absorption_rz, reflectance_ra, transmittance_ra;  // [r][z] and [r][a], row-major
    std::vector<Estimate> reflectance_within, transmittance_within;  // per RteRequest::within_radii_cm: diffuse, fractions
    std::uint64_t photons = 0;
    std::uint64_t truncated_photons = 0;
    bool partial = false;
};

RteResult solve_rte(const RteRequest& request);

// Absorption replay: one white trace of the request's geometry and scattering re-weighted for every set (mu_a per
// layer, 1/cm); one result per set, each equal to its own white run (request.white with that mu_a) to rounding.
// A stderr target is met by every set.
std::vector<RteResult> solve_rte_sets(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets);

// Exit replay, for radial profiles of many absorption sets at the cost of one walk: one white trace at the floor
// absorption (per layer the least of the sets; its analog absorption ends the long paths no set would weigh), each
// exit's path length per layer recorded, and each set's exit weighed by exp(-sum_k (mu_a,k - floor_k) L_k) (white
// Monte Carlo re-weighting, Alerstam et al. 2008). The walk's cost does not grow with the sets; each set costs a
// vectorised exponential per exit. Escapes only: specular, diffuse R, T, R_r, T_r (per-photon standard errors) and the
// within-radius channels per set, the absorption and angle grids refused (nz = na = 0), the absorbed fractions not
// computed. A stderr target is met by every set.
std::vector<RteResult> solve_rte_exit_sets(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets);

// A material's spectra with the volumetric walk, in the shared result type and schema (model "rte"):
// R = specular + diffuse, R_specular, T, A per layer; requires volumetric scattering in every layer.
SpectralResult solve_rte_spectrum(const LayerStack& stack, const SpectralRequest& request, BoundaryMode boundaries = BoundaryMode::random);

// A homogeneous band material's band as the walk's medium: isotropic scattering with mu_s = sigma_s' (the material
// gives reduced scattering only; the similarity relation, Wyman et al. 1989), its refractive index against air, in a
// slab deep enough to stand for the semi-infinite medium (rte_solver.cpp says how deep).
inline constexpr double band_slab_min_mean_free_paths = 200.0, band_slab_max_mean_free_paths = 1e4;
inline constexpr double band_slab_transmittance_worth_a_warning = 1e-6;
RteStack rte_band_slab(const HomogeneousMaterial& material, std::size_t band);
// R, T, A per band of `material` (rows named by material.bands, wavelength 0), T ~ 0 by construction.
SpectralResult solve_rte_bands(const HomogeneousMaterial& material, const SpectralRequest& request, BoundaryMode boundaries = BoundaryMode::random);
// Absorption replay of stacks that differ only in absorbers (white Monte Carlo, one trace per wavelength), one
// result per stack; `white` with one stack: its own white run (what a replayed set equals to rounding).
std::vector<SpectralResult> solve_rte_spectra(const std::vector<const LayerStack*>& stacks, const SpectralRequest& request,
                                              BoundaryMode boundaries, bool white);

}  // namespace skinspec
