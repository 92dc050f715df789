#pragma once
// Chromophores: tabulated absorption spectra from data/chromophores and the Beer-Lambert conversions from
// extinction to the absorption coefficient mu_a in 1/cm.
#include <string_view>
#include <vector>

#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

enum class ChromophoreKind {
    eumelanin,        // mass extinction, cm^-1 / (mg/mL)      (Sarna & Swartz)
    pheomelanin,      // mass extinction, cm^-1 / (mg/mL)      (Sarna & Swartz)
    oxyhemoglobin,    // molar extinction, cm^-1 / M, decadic  (Prahl)
    deoxyhemoglobin,  // molar extinction, cm^-1 / M, decadic  (Prahl)
    bilirubin,        // molar extinction, cm^-1 / M, decadic  (PhotochemCAD)
    beta_carotene,    // molar extinction, cm^-1 / M, decadic  (PhotochemCAD)
    water,            // absorption coefficient, cm^-1         (Segelstein)
    lipid,            // absorption coefficient, cm^-1         (van Veen, 429-1098 nm)
    baseline_tissue,  // absorption coefficient, cm^-1         (Jacques' bloodless-tissue formula)
};

enum class ExtinctionUnits { mass_per_cm_per_mg_per_ml, molar_decadic_per_cm_per_molar, absorption_per_cm };

struct Chromophore {
    ChromophoreKind kind;
    ExtinctionUnits units;
    TabulatedSpectrum table;  // with the data file's own out-of-range policy
};

// Loaded once from data/chromophores (thread-safe).
const Chromophore& chromophore(ChromophoreKind kind);
const std::vector<ChromophoreKind>& all_chromophores();
std::string_view name(ChromophoreKind kind);
std::string_view units_text(ExtinctionUnits units);

// Whether the decadic extinction of a table is turned into a natural (Napierian) absorption coefficient.
enum class DecadicConversion {
    multiply_ln10,  // mu_a = ln(10) * epsilon * c: Beer-Lambert with decadic extinction (the physics)
    omit_ln10,      // mu_a = epsilon * c: what the 2004 BioSpec implementations did (compatibility switch)
};

// mu_a [1/cm] = (ln 10) * epsilon [cm^-1 M^-1] * c [g/L] / M [g/mol]  (Beer-Lambert; c / M in mol/L).
double mu_a_from_molar_extinction_per_cm(double epsilon_per_cm_per_molar, double concentration_g_per_l,
                                         double molar_mass_g_per_mol, DecadicConversion conversion);
// mu_a [1/cm] = (ln 10) * epsilon [cm^-1 / (mg/mL)] * c [mg/mL]. BioSpec uses the melanin tables with omit_ln10.
double mu_a_from_mass_extinction_per_cm(double epsilon_per_cm_per_mg_per_ml, double concentration_mg_per_ml,
                                        DecadicConversion conversion);

// Unit helpers: 1 g/L = 1 mg/mL; 1 mm^-1 = 10 cm^-1.
constexpr double mg_per_ml_from_g_per_l(double g_per_l) { return g_per_l; }
constexpr double per_cm_from_per_mm(double per_mm) { return per_mm * 10.0; }
constexpr double per_mm_from_per_cm(double per_cm) { return per_cm / 10.0; }

}  // namespace skinspec
