#pragma once
// The BioSpec model (Krishnaswamy & Baranoski 2004; docs/BIOSPEC.md, "One ray" and "Where a Rayleigh-scattered ray turns") solved
// deterministically by adding (transport/adding_doubling/ad_elements.hpp): every rule of the walk is a linear operator
// on the flux per direction channel, and the walk's R, T and A are their adding.
//  - SC and epidermis, each crossing: a deflection drawn from the layer's measured profile (or HG), re-drawn while it
//    would reverse the travel sense: the profile's redistribution (delta-M Legendre series, as the volumetric layers')
//    restricted to the travel hemisphere and renormalised, then exp(-mu_a d / cos) along the new direction.
//  - Dermal layers going down: with probability exp(-beta d / cos_in) a cosine-distributed direction, else one
//    Rayleigh turn at depth z (density beta / cos_in exp(-(beta + mu_a) z / cos_in)) and exp(-mu_a z / cos_out) back up
//    or exp(-mu_a (d - z) / cos_out) on down (closed-form integrals over z); going up: a cosine-distributed direction.
//  - Fresnel at every interface (the walk's unpolarised reflectance), the Lambertian reflector or the exit below, and
//    the skin fold at the surface: a fold-perturbed reflection that points into the skin is lost (A_surface) unless
//    re-drawn (fold_into_skin = resample).
// It is the walk's model with no noise: R, T, A per layer agree with the walk within its standard errors plus the
// quadrature's accuracy (docs/ADDING_DOUBLING.md). Angular bins and the 0/45 geometry are the walk's alone.
#include <optional>

#include "materials/layer_stack.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/biospec/biospec_options.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

struct BiospecAdOptions {
    AdOptions ad;
    FoldIntoSkin fold_into_skin = FoldIntoSkin::drop;
    std::optional<ThinLayerHg> thin_layer_hg;  // unset: the measured profiles
};

struct BiospecAdResult {
    AdResult totals;               // specular_reflectance: what the skin fold lets leave
    double surface_absorbed = 0.0;  // the fold's lost reflection (A_surface)
};

// InputError for the authors'-code behaviours it does not model (swapped upward indices, SC reversals kept).
BiospecAdResult solve_biospec_adding_doubling(const LayerStack& stack, double wavelength_nm, double incidence_deg, const BiospecAdOptions& options,
                                              AdCache* cache = nullptr);

// A spectrum in the shared result type (model "biospec-adding-doubling"): R in the request's geometry (sci, sce),
// R_specular, T, A per layer, A_surface; deterministic, with the quadrature's stated error.
SpectralResult solve_biospec_adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const BiospecAdOptions& options);

}  // namespace skinspec
