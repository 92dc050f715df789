#include <catch2/catch.hpp>

#include <cmath>

#include "materials/chromophore.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("molar extinction converts to mu_a by Beer-Lambert", "[chromophore]") {
    // Issue check value: whole blood 150 g/L, HbO2 at 576 nm (eps 55540 cm^-1/M, Prahl), M = 64,500 g/mol:
    // ln10 * 55540 * 150 / 64500 = 297.4 /cm.
    const double eps = chromophore(ChromophoreKind::oxyhemoglobin).table(576.0);
    CHECK(eps == 55540.0);
    CHECK(mu_a_from_molar_extinction_per_cm(eps, 150.0, 64500.0, DecadicConversion::multiply_ln10) == Approx(297.408).margin(1e-3));
    // The 2004 compatibility switch omits ln 10.
    CHECK(mu_a_from_molar_extinction_per_cm(eps, 150.0, 64500.0, DecadicConversion::omit_ln10) ==
          Approx(55540.0 * 150.0 / 64500.0));
    // With the reference implementation's 66,500 g/mol.
    CHECK(mu_a_from_molar_extinction_per_cm(eps, 150.0, 66500.0, DecadicConversion::multiply_ln10) ==
          Approx(std::log(10.0) * 55540.0 * 150.0 / 66500.0));
}

TEST_CASE("tables hold the published values at tabulated wavelengths", "[chromophore]") {
    // ../shared/data-sources/SOURCES.md check values and raw rows.
    CHECK(chromophore(ChromophoreKind::oxyhemoglobin).table(542.0) == 53292.0);
    CHECK(chromophore(ChromophoreKind::deoxyhemoglobin).table(560.0) == 53788.0);
    CHECK(chromophore(ChromophoreKind::eumelanin).table(642.77) == 3.28);
    CHECK(chromophore(ChromophoreKind::beta_carotene).table(450.99) == 139500.0);
    CHECK(chromophore(ChromophoreKind::water).table(600.0) == Approx(0.0020184));
    // Jacques' baseline: 0.244 + 85.3 exp(-(500 - 154) / 66.2) = 0.70222 /cm.
    CHECK(chromophore(ChromophoreKind::baseline_tissue).table(500.0) == Approx(0.702217).margin(1e-6));
    // Between 1 nm samples the tabulated formula stays within 3e-5 relative of the formula.
    CHECK(chromophore(ChromophoreKind::baseline_tissue).table(500.5) ==
          Approx(0.244 + 85.3 * std::exp(-(500.5 - 154.0) / 66.2)).epsilon(3e-5));
    // Melanin mass extinction: mu_a = eps * c, 80 mg/mL eumelanin at 642.77 nm -> 262.4 /cm without ln 10.
    CHECK(mu_a_from_mass_extinction_per_cm(3.28, 80.0, DecadicConversion::omit_ln10) == Approx(262.4));
}

TEST_CASE("negative PhotochemCAD tails are clamped to zero", "[chromophore]") {
    for (const auto kind : {ChromophoreKind::beta_carotene, ChromophoreKind::bilirubin}) {
        for (const double v : chromophore(kind).table.values()) CHECK(v >= 0.0);
    }
}

TEST_CASE("each chromophore's out-of-range policy is explicit", "[chromophore]") {
    // Melanins, haemoglobin, water and the baseline: asking outside the table is an error naming it.
    CHECK_THROWS_WITH(chromophore(ChromophoreKind::eumelanin).table(2600.0),
                      Catch::Contains("eumelanin: wavelength 2600 nm is outside the tabulated domain"));
    CHECK_THROWS_AS(chromophore(ChromophoreKind::oxyhemoglobin).table(2600.0), InputError);
    CHECK_THROWS_AS(chromophore(ChromophoreKind::baseline_tissue).table(200.0), InputError);
    CHECK_THROWS_WITH(chromophore(ChromophoreKind::lipid).table(1100.0),
                      Catch::Contains("lipid: wavelength 1100 nm is outside the tabulated domain [429, 1098] nm"));
    // Carotene and bilirubin: zero above 700 nm, where their absorption is nil.
    CHECK(chromophore(ChromophoreKind::beta_carotene).table(750.0) == 0.0);
    CHECK(chromophore(ChromophoreKind::bilirubin).table(750.0) == 0.0);
}

TEST_CASE("unit helpers", "[chromophore]") {
    CHECK(per_cm_from_per_mm(1.5) == 15.0);
    CHECK(per_mm_from_per_cm(15.0) == 1.5);
    CHECK(mg_per_ml_from_g_per_l(2.0) == 2.0);
    CHECK(name(ChromophoreKind::beta_carotene) == "beta-carotene");
    CHECK(units_text(chromophore(ChromophoreKind::eumelanin).units) == "cm^-1/(mg/mL)");
}

TEST_CASE("tables reach 2500 nm by their documented laws, continuous with the measurements", "[chromophore]") {
    // Raw rows: Segelstein water 31.542 /cm at 1449 nm; van Veen fat 13.10 /m at 930 nm.
    CHECK(chromophore(ChromophoreKind::water).table(1449.0) == Approx(31.542));
    CHECK(chromophore(ChromophoreKind::lipid).table(930.0) == Approx(0.131));
    // Melanin in the near infrared: Jacques (1996, OMLC 'Melanosome absorption coefficient') models the melanosome
    // absorption as lambda^-3.33 .. lambda^-3.48; the tail fitted to Sarna's 600-830 nm must fall in that band.
    const auto& eu = chromophore(ChromophoreKind::eumelanin).table;
    const double ratio = eu(2000.0) / eu(1000.0);
    CHECK(ratio < std::pow(2.0, -3.33));
    CHECK(ratio > std::pow(2.0, -3.48));
    // Haemoglobin: the measured 1000 nm row stays, the tail decays monotonically from it.
    const auto& oxy = chromophore(ChromophoreKind::oxyhemoglobin).table;
    CHECK(oxy(1000.0) == 1024.0);
    double previous = oxy(1000.0);
    for (double nm = 1010.0; nm <= 2500.0; nm += 10.0) {
        CHECK(oxy(nm) < previous);
        previous = oxy(nm);
    }
    // Every table with an 'error' policy refuses past 2500 nm (no silent extrapolation).
    for (const auto kind : {ChromophoreKind::eumelanin, ChromophoreKind::pheomelanin, ChromophoreKind::oxyhemoglobin,
                            ChromophoreKind::water, ChromophoreKind::baseline_tissue}) {
        CHECK_NOTHROW(chromophore(kind).table(2500.0));
        CHECK_THROWS_AS(chromophore(kind).table(2501.0), InputError);
    }
}
