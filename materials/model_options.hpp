#pragma once
// BioSpec model variants (docs/MATERIALS.md "Model variants"; docs/BIOSPEC.md "The model authors' current code"):
// named option sets whose every switch can also be set on its own.
#include <string>
#include <string_view>
#include <vector>

#include "materials/chromophore.hpp"

namespace skinspec {

// Where a ray Rayleigh-scattered in a dermal layer turns, and so which path its absorption is charged over
// (docs/BIOSPEC.md, "Where a Rayleigh-scattered ray turns").
enum class RayleighTurn {
    sampled_depth,   // free path s ~ Exp(beta) along the incoming direction; turn at depth s |cos_in| (default)
    whole_crossing,  // the 2004 text: the whole crossing charged along the new direction
    no_absorption,   // the authors' current code: a ray turned upward is charged nothing in that layer
};
std::string_view to_string(RayleighTurn turn);
RayleighTurn parse_rayleigh_turn(std::string_view text, std::string_view what);

// The skin-fold perturbation of the surface reflection (docs/BIOSPEC.md, "One ray" step 1 and the authors' behaviour 5).
enum class FoldFormula {
    biospec_2004,  // theta = arccos(sqrt((sigma^2 / sqrt(sigma^4 + (1 - sigma^4) u) - 1) / (sigma^2 - 1)))
    authors_code,  // theta = arccos(sqrt((1 - u) / (u (sigma^2 - 1) + 1)))
};
std::string_view to_string(FoldFormula formula);
FoldFormula parse_fold_formula(std::string_view text, std::string_view what);

struct ModelOptions {
    std::string variant = "biospec";
    bool dermal_rayleigh = true;                  // Rayleigh scattering by collagen fibres in dermal layers
    DecadicConversion molar_tables = DecadicConversion::multiply_ln10;  // haemoglobin, bilirubin, carotene
    DecadicConversion melanin_tables = DecadicConversion::omit_ln10;    // as the reference implementation
    bool baseline_absorption = true;              // Jacques' bloodless-tissue absorption in the background
    double hemoglobin_molar_mass_g_per_mol = 66500.0;  // reference implementation; Prahl uses 64,500
    double bilirubin_molar_mass_g_per_mol = 585.0;
    double carotene_molar_mass_g_per_mol = 537.0;
    RayleighTurn rayleigh_turn = RayleighTurn::sampled_depth;
    // The authors' code's behaviours (docs/BIOSPEC.md, "The model authors' current code", numbered as there); the defaults are the specification's.
    bool swapped_upward_indices = false;  // 1: upward crossings evaluate the interface with its indices swapped
    bool bottom_exit_fresnel = true;      // 3: false = light leaves the bottom (reflector off) with no Fresnel test
    bool redraw_reversals_in_stratum_corneum = true;  // 4: false = a reversing SC perturbation is kept (see walk)
    FoldFormula fold_formula = FoldFormula::biospec_2004;  // 5
    // The volumetric solvers solve a description derived from the BioSpec one (transport/adding_doubling/
    // matched_volumetric.hpp) instead of the layers' own volumetric fields.
    bool volumetric_matched_to_biospec = false;

    bool operator==(const ModelOptions&) const = default;
};

// "biospec" (the corrected model), "biospec-2004" (as the 2004 code behaved, outright defects excluded) or
// "biospec-authors-code" (the corrected model with the behaviours of the authors' current code: reproduces
// their published figures, not physics). InputError naming `what` for an unknown name.
ModelOptions model_variant(std::string_view name, std::string_view what);
const std::vector<std::string_view>& model_variant_names();

}  // namespace skinspec
