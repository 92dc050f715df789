#pragma once
// A layer stack: the medium above, ordered tissue layers (top first), the bottom boundary, the surface's
// fold aspect ratio and the model options. Answers "what are the optics of layer k at wavelength lambda?".
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "materials/tissue_layer.hpp"
#include "materials/measured_profile.hpp"

namespace skinspec {

enum class BottomBoundary {
    diffuse_reflector,  // BioSpec's hypodermis: ideal Lambertian reflector, R = 1
    // The measured hypodermis (Salomatina et al. 2006) as a Lambertian reflector of its semi-infinite diffuse
    // reflectance (transport/adding_doubling/hypodermis_reflectance.hpp); what it does not return is T.
    hypodermis,
    exit,  // light leaving the last layer enters a medium of below_refractive_index (transmittance)
};
// A reflector below the last layer (diffuse_reflector or hypodermis).
inline bool has_reflector(BottomBoundary kind) { return kind != BottomBoundary::exit; }
std::string_view to_string(BottomBoundary kind);
BottomBoundary parse_bottom_boundary(std::string_view text, std::string_view what);

// Optics of one layer at one wavelength, in the units the solvers use.
struct LayerOptics {
    double thickness_cm;
    double refractive_index;
    double mu_a_per_cm;
    CrossingScattering crossing;          // effective: rayleigh_cosine becomes cosine when Rayleigh is off
    double hg_g;                          // for henyey_greenstein crossings
    double rayleigh_per_cm;               // collagen Rayleigh coefficient (0 unless rayleigh_cosine)
    double mie_reduced_per_cm;            // Mie reduced scattering of the turn test (0 unless rayleigh_cosine)
    std::optional<double> mu_s_per_cm;    // volumetric scattering, when described
    std::optional<PhaseFunctionKind> phase;
    std::optional<double> g;
    std::optional<double> mu_s_reduced_per_cm;  // reduced scattering, when described
    std::shared_ptr<const InverseCdfTable> phase_table;  // measured phases: the profile at this wavelength

    // The coefficient of a rayleigh_cosine crossing's turn test: Rayleigh and Mie (tissue_layer.hpp).
    double turn_per_cm() const { return rayleigh_per_cm + mie_reduced_per_cm; }
};

// Which optional descriptions to evaluate: a solver asks only for what it uses, so e.g. the BioSpec walk
// does not need the reduced-scattering table to cover its wavelengths.
struct OpticsScope {
    bool volumetric = true;
    bool reduced = true;
};

// How a layer's crossings scatter in effect: rayleigh_cosine becomes cosine when model.dermal_rayleigh is off.
CrossingScattering crossing_in_effect(const TissueLayer& layer, const ModelOptions& model);

struct LayerStack {
    std::string name;
    std::string description;
    double above_refractive_index = 1.0;
    std::vector<TissueLayer> layers;
    BottomBoundary bottom = BottomBoundary::diffuse_reflector;
    double below_refractive_index = 1.0;
    double fold_aspect_ratio = 0.75;  // skin-fold perturbation of surface reflection, sigma in (0, 1]
    ModelOptions model;

    LayerOptics optics(std::size_t layer, double wavelength_nm, OpticsScope scope = {}) const;
    std::vector<LayerOptics> optics(double wavelength_nm, OpticsScope scope = {}) const;

    // The stack with only the named layers, in stack order (e.g. stratum_corneum + epidermis, as measured
    // in vitro); InputError naming an unknown layer.
    LayerStack sub_stack(const std::vector<std::string>& layer_names) const;

    bool operator==(const LayerStack&) const = default;
};

}  // namespace skinspec
