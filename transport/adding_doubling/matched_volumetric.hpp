#pragma once
// The volumetric description derived from the BioSpec description (model.volumetric_matched_to_biospec; issue 31,
// "one skin"): what the volumetric solvers (adding-doubling, the volumetric walk, diffusion's stated error, the
// renderer exports) solve when a material asks for it, so that they describe the skin the BioSpec walk describes.
//  - A layer whose crossings deflect once by a profile (SC, epidermis: measured or HG crossings) scatters
//    volumetrically with mu_s = 1 / d (one deflection per normal crossing, as the walk's one per crossing) and the
//    crossing's own redistribution as its phase function (the measured profile at the wavelength, or HG with hg_g).
//  - The dermal layers (cosine and Rayleigh crossings, which no reciprocal medium reproduces: the walk's dermis
//    transmits every upward crossing diffusely and reflects none) keep their phase function; their mu_s is scaled
//    by one factor per wavelength, found so that adding-doubling's diffuse reflectance of the whole stack equals
//    biospec-adding-doubling's (the BioSpec model solved exactly) at normal incidence: the albedo matching of
//    production renderers, with the factor found by root finding (the largest root: R grows with the scale there).
// Where no dermal factor reaches the target (heavily pigmented skin in the red: R_d has a minimum above it), the thin
// layers' mu_s moves from 1 / d by the least factor (up to 4 either way) that lets one: their scattering lengthens the
// paths through the melanin as the walk's deflections do.
// The dermal factor follows the Rayleigh law the BioSpec dermis scatters by (~lambda^-4; docs/ADDING_DOUBLING.md).
#include "materials/layer_stack.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {

struct MatchedVolumetric {
    RteStack stack;             // the derived description
    double thin_scale = 1.0;    // the factor on the thin layers' mu_s d = 1 (1 unless the dermis alone cannot match)
    double dermal_scale = 1.0;  // the factor on the dermal layers' mu_s
    double residual = 0.0;      // |R_d derived - R_d BioSpec| where no factor reaches it (0 where one does)
};

// Channels of the two solves the match compares (both at the same count: their quadrature errors largely cancel).
inline constexpr std::size_t matched_volumetric_channels = 16;

// `tables`: the layers' own volumetric description at `wavelength_nm` (rte_stack_from). InputError when the stack
// has no dermal layer to scale or a model switch biospec-adding-doubling does not model.
MatchedVolumetric match_volumetric_to_biospec(const LayerStack& stack, const RteStack& tables, double wavelength_nm);

// The derived description's miss of the BioSpec model at one wavelength and incidence: R of `derived` (adding-doubling
// of the derived description at `incidence_deg`) less R of biospec-adding-doubling of `stack` there, at the same
// channels; the specular reflection counts unless `specular` is false (geometry sce). 0 to the match's tolerance at
// normal incidence where a factor reaches R_d; up to ~0.04 at 60 deg (docs/ADDING_DOUBLING.md).
double derived_description_miss(const LayerStack& stack, const AdResult& derived, double wavelength_nm, double incidence_deg, bool specular,
                                const AdOptions& options, AdCache* cache = nullptr);

}  // namespace skinspec
