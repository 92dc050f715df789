#pragma once
// Materials in the diffusion modes: which slabs a layered skin stack or a homogeneous (RGB-band) material
// becomes at one wavelength, whether diffusion can be trusted there, and spectra in the shared result format.
//
// Per layer: sigma_a from the materials model (the same mu_a as the walks), sigma_s' from the layer's reduced
// scattering description (Salomatina's measured epidermis/dermis tables or a power law; docs/DIFFUSION.md),
// index of refraction per layer. Units: mm and 1/mm (profiles are per mm^2).
//   multipole: every layer a slab (Donner & Jensen 2005), composed in frequency space; layers thinner than 0.7 transport
//              mean free paths are merged with the next (thickness-weighted coefficients) because diffusion
//              cannot resolve them, layers of 0.7-1.4 are merged and kept, the two stacks blended smoothly (no
//              jump in wavelength); the hypodermis reflector (ideal or measured) or the open bottom as the material says.
//   dipole:    the whole material as one semi-infinite medium (Jensen et al. 2001) with depth-averaged coefficients.
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
// Around the one transport mean free path below which a layer used to be merged (a factor sqrt(2) each way):
constexpr double diffusion_merge_fully_below_mfp = 0.7;  // a thinner layer is merged with its neighbour
constexpr double diffusion_merge_none_above_mfp = 1.4;   // a thicker one is kept; in between, both, blended

// One finding outside the trusted range, e.g. {"epidermis", "reduced albedo 0.62 is below 0.9"}.
struct TrustWarning {
    std::string slab;
    std::string kind;   // "albedo", "thin", "merged"
    double value = 0;   // the albedo, or the thickness in mean free paths
};

struct WeightedStack {
    double weight;
    LayeredDiffusion stack;
};

// A material at one wavelength (or band), ready to evaluate.
struct DiffusionMaterial {
    std::vector<std::string> slab_names;  // of the heaviest stack; merged layers are joined with '+'
    std::vector<WeightedStack> stacks;    // one, or where a layer is half merged each way, weights summing to 1
    double specular_reflectance = 0.0;    // first-surface reflection at the incidence
    double entry_transmittance = 1.0;     // 1 - specular: what enters and diffuses
    std::vector<TrustWarning> warnings;

    double diffuse_reflectance() const;  // per unit incident power (entry transmittance included)
    double total_reflectance() const { return specular_reflectance + diffuse_reflectance(); }
    double total_transmittance() const;
    // Diffuse profiles per unit incident power (entry transmittance included), per mm^2 at radii in mm.
    RadialProfile reflectance_profile(std::span<const double> radii_mm, const std::atomic<bool>* cancel = nullptr) const;
    RadialProfile transmittance_profile(std::span<const double> radii_mm, const std::atomic<bool>* cancel = nullptr) const;
};

DiffusionMaterial diffusion_material(const LayerStack& stack, double wavelength_nm, const DiffusionOptions& options,
                                     double incidence_deg = 0.0);
DiffusionMaterial diffusion_material(const HomogeneousMaterial& material, std::size_t band, const DiffusionOptions& options,
                                     double incidence_deg = 0.0);

// The finding as a result warning, `at` the wavelength or band ("400 nm", "band R"); its kind starts with this.
inline constexpr std::string_view diffusion_warning_prefix = "diffusion: ";
ResultWarning result_warning(const TrustWarning& warning, const std::string& at);

// Spectra in the shared format (no standard errors: has_uncertainty is false). Quantities R and T only
// (InputError for A or angular). Bands of a homogeneous material are reported in the file's order.
SpectralResult solve_diffusion_spectrum(const LayerStack& stack, const SpectralRequest& request, const DiffusionOptions& options);
SpectralResult solve_diffusion_bands(const HomogeneousMaterial& material, const SpectralRequest& request, const DiffusionOptions& options);

}  // namespace skinspec
