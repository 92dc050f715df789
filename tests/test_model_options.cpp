#include <catch2/catch.hpp>

#include "materials/model_options.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("the BioSpec variants set the documented switches", "[model_options]") {
    const auto corrected = model_variant("biospec", "v");
    CHECK(corrected.dermal_rayleigh);
    CHECK(corrected.molar_tables == DecadicConversion::multiply_ln10);
    CHECK(corrected.melanin_tables == DecadicConversion::omit_ln10);
    CHECK(corrected.baseline_absorption);
    CHECK(corrected.hemoglobin_molar_mass_g_per_mol == 66500.0);
    CHECK(corrected.rayleigh_turn == RayleighTurn::sampled_depth);
    CHECK_FALSE(corrected.swapped_upward_indices);
    CHECK(corrected.bottom_exit_fresnel);
    CHECK(corrected.redraw_reversals_in_stratum_corneum);
    CHECK(corrected.fold_formula == FoldFormula::biospec_2004);
    const auto old = model_variant("biospec-2004", "v");
    CHECK_FALSE(old.dermal_rayleigh);
    CHECK(old.molar_tables == DecadicConversion::omit_ln10);
    CHECK(old.melanin_tables == DecadicConversion::omit_ln10);
    CHECK_FALSE(old.baseline_absorption);
    CHECK(old.hemoglobin_molar_mass_g_per_mol == 66500.0);
    // The authors' current code: the corrected model's absorption with the five behaviours of the audit.
    auto authors = model_variant("biospec-authors-code", "v");
    CHECK(authors.rayleigh_turn == RayleighTurn::no_absorption);
    CHECK(authors.swapped_upward_indices);
    CHECK_FALSE(authors.bottom_exit_fresnel);
    CHECK_FALSE(authors.redraw_reversals_in_stratum_corneum);
    CHECK(authors.fold_formula == FoldFormula::authors_code);
    authors.variant = corrected.variant;
    authors.rayleigh_turn = corrected.rayleigh_turn;
    authors.swapped_upward_indices = false;
    authors.bottom_exit_fresnel = true;
    authors.redraw_reversals_in_stratum_corneum = true;
    authors.fold_formula = FoldFormula::biospec_2004;
    CHECK(authors == corrected);
    CHECK_THROWS_WITH(model_variant("biospec-1999", "model.variant"),
                      "model.variant: 'biospec-1999' is not a model variant (allowed: biospec, biospec-2004, biospec-authors-code)");
    CHECK_THROWS_WITH(parse_rayleigh_turn("depth", "model.rayleigh_turn"),
                      "model.rayleigh_turn: 'depth' is not a Rayleigh turn rule (allowed: sampled_depth, whole_crossing, no_absorption)");
    CHECK(parse_fold_formula("authors_code", "f") == FoldFormula::authors_code);
}
