#include <catch2/catch.hpp>

#include "materials/model_options.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("the two BioSpec variants set the documented switches", "[model_options]") {
    const auto corrected = model_variant("biospec", "v");
    CHECK(corrected.dermal_rayleigh);
    CHECK(corrected.molar_tables == DecadicConversion::multiply_ln10);
    CHECK(corrected.melanin_tables == DecadicConversion::omit_ln10);
    CHECK(corrected.baseline_absorption);
    CHECK(corrected.hemoglobin_molar_mass_g_per_mol == 66500.0);
    const auto old = model_variant("biospec-2004", "v");
    CHECK_FALSE(old.dermal_rayleigh);
    CHECK(old.molar_tables == DecadicConversion::omit_ln10);
    CHECK(old.melanin_tables == DecadicConversion::omit_ln10);
    CHECK_FALSE(old.baseline_absorption);
    CHECK(old.hemoglobin_molar_mass_g_per_mol == 66500.0);
    CHECK_THROWS_WITH(model_variant("biospec-1999", "model.variant"),
                      "model.variant: 'biospec-1999' is not a model variant (allowed: biospec, biospec-2004)");
}
