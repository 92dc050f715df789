#include "materials/chromophore.hpp"

#include <numbers>
#include <string>

#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"
#include "spectral/load_once.hpp"

namespace skinspec {
namespace {

struct TableSource {
    ExtinctionUnits units;
    const char* file;
    const char* column;
};

// Indexed by ChromophoreKind.
constexpr TableSource sources[] = {
    {ExtinctionUnits::mass_per_cm_per_mg_per_ml, "chromophores/eumelanin.csv", "mass_extinction"},
    {ExtinctionUnits::mass_per_cm_per_mg_per_ml, "chromophores/pheomelanin.csv", "mass_extinction"},
    {ExtinctionUnits::molar_decadic_per_cm_per_molar, "chromophores/hemoglobin.csv", "oxy"},
    {ExtinctionUnits::molar_decadic_per_cm_per_molar, "chromophores/hemoglobin.csv", "deoxy"},
    {ExtinctionUnits::molar_decadic_per_cm_per_molar, "chromophores/bilirubin.csv", "molar_extinction"},
    {ExtinctionUnits::molar_decadic_per_cm_per_molar, "chromophores/beta_carotene.csv", "molar_extinction"},
    {ExtinctionUnits::absorption_per_cm, "chromophores/water.csv", "mu_a"},
    {ExtinctionUnits::absorption_per_cm, "chromophores/lipid.csv", "mu_a"},
    {ExtinctionUnits::absorption_per_cm, "chromophores/baseline_tissue.csv", "mu_a"},
};

Chromophore load(ChromophoreKind kind) {
    const auto& source = sources[static_cast<std::size_t>(kind)];
    return {kind, source.units,
            DataTable::read(data_file(source.file)).spectrum(source.column, std::string(name(kind)))};
}

double factor(DecadicConversion conversion) {
    return conversion == DecadicConversion::multiply_ln10 ? std::numbers::ln10 : 1.0;
}

}  // namespace

const std::vector<ChromophoreKind>& all_chromophores() {
    static const std::vector<ChromophoreKind> kinds{
        ChromophoreKind::eumelanin, ChromophoreKind::pheomelanin,   ChromophoreKind::oxyhemoglobin,
        ChromophoreKind::deoxyhemoglobin, ChromophoreKind::bilirubin, ChromophoreKind::beta_carotene,
        ChromophoreKind::water,     ChromophoreKind::lipid,         ChromophoreKind::baseline_tissue};
    return kinds;
}

const Chromophore& chromophore(ChromophoreKind kind) { return load_once(kind, all_chromophores(), load); }

std::string_view name(ChromophoreKind kind) {
    switch (kind) {
        case ChromophoreKind::eumelanin: return "eumelanin";
        case ChromophoreKind::pheomelanin: return "pheomelanin";
        case ChromophoreKind::oxyhemoglobin: return "oxyhaemoglobin";
        case ChromophoreKind::deoxyhemoglobin: return "deoxyhaemoglobin";
        case ChromophoreKind::bilirubin: return "bilirubin";
        case ChromophoreKind::beta_carotene: return "beta-carotene";
        case ChromophoreKind::water: return "water";
        case ChromophoreKind::lipid: return "lipid";
        case ChromophoreKind::baseline_tissue: return "baseline tissue";
    }
    return "?";
}

std::string_view units_text(ExtinctionUnits units) {
    switch (units) {
        case ExtinctionUnits::mass_per_cm_per_mg_per_ml: return "cm^-1/(mg/mL)";
        case ExtinctionUnits::molar_decadic_per_cm_per_molar: return "cm^-1/M (decadic)";
        case ExtinctionUnits::absorption_per_cm: return "cm^-1";
    }
    return "?";
}

double mu_a_from_molar_extinction_per_cm(double epsilon_per_cm_per_molar, double concentration_g_per_l,
                                         double molar_mass_g_per_mol, DecadicConversion conversion) {
    return factor(conversion) * epsilon_per_cm_per_molar * concentration_g_per_l / molar_mass_g_per_mol;
}

double mu_a_from_mass_extinction_per_cm(double epsilon_per_cm_per_mg_per_ml, double concentration_mg_per_ml,
                                        DecadicConversion conversion) {
    return factor(conversion) * epsilon_per_cm_per_mg_per_ml * concentration_mg_per_ml;
}

}  // namespace skinspec
