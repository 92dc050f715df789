#pragma once
// BioSpec model variants (docs/MATERIALS.md, shared spec "Model variants"): named option sets whose every
// switch can also be set on its own.
#include <string>
#include <string_view>

#include "materials/chromophore.hpp"

namespace skinspec {

struct ModelOptions {
    std::string variant = "biospec";
    bool dermal_rayleigh = true;                  // Rayleigh scattering by collagen fibres in dermal layers
    DecadicConversion molar_tables = DecadicConversion::multiply_ln10;  // haemoglobin, bilirubin, carotene
    DecadicConversion melanin_tables = DecadicConversion::omit_ln10;    // as the reference implementation
    bool baseline_absorption = true;              // Jacques' bloodless-tissue absorption in the background
    double hemoglobin_molar_mass_g_per_mol = 66500.0;  // reference implementation; Prahl uses 64,500
    double bilirubin_molar_mass_g_per_mol = 585.0;
    double carotene_molar_mass_g_per_mol = 537.0;

    bool operator==(const ModelOptions&) const = default;
};

// "biospec" (the corrected model) or "biospec-2004" (as the 2004 code behaved, outright defects excluded).
// InputError naming `what` for an unknown name.
ModelOptions model_variant(std::string_view name, std::string_view what);

}  // namespace skinspec
