#pragma once
// The measured hypodermis as the skin's bottom (bottom.boundary = hypodermis; issue 35, docs/HYPERSPECTRAL.md): a
// Lambertian reflector whose reflectance is the diffuse (white-sky) reflectance of a semi-infinite layer of ex-vivo
// human hypodermis, Salomatina et al. 2006 (J. Biomed. Opt. 11:064026) mu_a and mu_s', index-matched to the skin
// above, solved by adding-doubling. BioSpec's hypodermis (diffuse_reflector) is the same reflector with reflectance 1.
#include "materials/layer_stack.hpp"

namespace skinspec {

// Henyey-Greenstein g with which mu_s = mu_s' / (1 - g) is built from the measured mu_s' (the dermis' volumetric g of
// the presets, van Gemert et al. 1989 at ~600 nm; Salomatina's inversion reports mu_s' only).
inline constexpr double hypodermis_g = 0.8;

// Diffuse reflectance of a semi-infinite, index-matched layer of mu_a, mu_s (1/cm) and HG phase g, for Lambertian
// incidence (adding-doubling at 32 channels).
double semi_infinite_diffuse_reflectance(double mu_a_per_cm, double mu_s_per_cm, double g);

// The measured hypodermis' reflectance at `wavelength_nm`; InputError outside its measured 373.7-1602.1 nm (no law
// continues Salomatina's mu_a). Computed once per wavelength per process.
double hypodermis_reflectance(double wavelength_nm);

// The reflectance of the stack's bottom reflector: 1 (diffuse_reflector), the measured hypodermis' (hypodermis), 0 with
// an open bottom (exit).
double bottom_reflectance(const LayerStack& stack, double wavelength_nm);

}  // namespace skinspec
