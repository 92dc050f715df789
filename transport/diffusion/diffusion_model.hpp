#pragma once
// Materials in the diffusion modes: which slabs a layered skin stack or a homogeneous (RGB-band) material
// becomes at one wavelength, whether diffusion can be trusted there, and spectra in the shared result format.
//
// Per layer: sigma_a from the materials model (the same mu_a as the walks), sigma_s' from the layer's reduced
// scattering description (Salomatina's measured epidermis/dermis tables or a power law; docs/DIFFUSION.md),
// index of refraction per layer. Units: mm and 1/mm (profiles are per mm^2).
//   multipole: every layer a slab (seed 002), composed in frequency space; layers thinner than one transport
//              mean free path are merged with the next (thickness-weighted coefficients) because diffusion
//              cannot resolve them; the hypodermis reflector or the open bottom as the material says.
//   dipole:    the whole material as one semi-infinite medium (seed 004) with depth-averaged coefficients.
// Trust (docs/DIFFUSION.md, backed by bench/diffusion_validation.cpp): reduced albedo >= 0.9 and, for
// finite slabs, thickness >= 2 transport mean free paths; results outside carry warnings.
#include <optional>
#include <string>
#include <vector>

#include "transport/diffusion/layered_diffusion.hpp"
#include "transport/spectral_request.hpp"
#include "materials/layer_stack.hpp"
#include "materials/material_file.hpp"

namespace skinspec {

enum class DiffusionMode { dipole, multipole };
std::string_view to_string(DiffusionMode mode);

struct DiffusionOptions {
    DiffusionMode mode = DiffusionMode::multipole;
    std::optional<double> surface_roughness;  // Beckmann RMS slope of a rough top surface; none = smooth
};

constexpr double diffusion_min_reduced_albedo = 0.9;
constexpr double diffusion_min_slab_mean_free_paths = 2.0;

// One finding outside the trusted range, e.g. {"epidermis", "reduced albedo 0.62 is below 0.9"}.
struct TrustWarning {
    std::string slab;
    std::string kind;   // "albedo", "thin", "merged"
    double value = 0;   // the albedo, or the thickness in mean free paths
    std::string text;
};

// A material at one wavelength (or band), ready to evaluate.
struct DiffusionMaterial {
    std::vector<std::string> slab_names;  // merged layers are joined with '+'
    LayeredDiffusion stack;
    double specular_reflectance = 0.0;  // first-surface reflection at the incidence
    double entry_transmittance = 1.0;   // 1 - specular: what enters and diffuses
    std::vector<TrustWarning> warnings;

    double total_reflectance() const { return specular_reflectance + entry_transmittance * stack.total_reflectance(); }
    double total_transmittance() const { return entry_transmittance * stack.total_transmittance(); }
    // Diffuse profiles per unit incident power (entry transmittance included), per mm^2 at radii in mm.
    RadialProfile reflectance_profile(std::span<const double> radii_mm) const;
    RadialProfile transmittance_profile(std::span<const double> radii_mm) const;
};

DiffusionMaterial diffusion_material(const LayerStack& stack, double wavelength_nm, const DiffusionOptions& options,
                                     double incidence_deg = 0.0);
DiffusionMaterial diffusion_material(const HomogeneousMaterial& material, std::size_t band, const DiffusionOptions& options,
                                     double incidence_deg = 0.0);

// The finding as a result warning, `at` the wavelength or band ("400 nm", "band R").
ResultWarning result_warning(const TrustWarning& warning, const std::string& at);

// Spectra in the shared format (no standard errors: has_uncertainty is false). Quantities R and T only
// (InputError for A or angular). Bands of a homogeneous material are reported in the file's order.
SpectralResult solve_diffusion_spectrum(const LayerStack& stack, const SpectralRequest& request, const DiffusionOptions& options);
SpectralResult solve_diffusion_bands(const HomogeneousMaterial& material, const SpectralRequest& request, const DiffusionOptions& options);

}  // namespace skinspec
