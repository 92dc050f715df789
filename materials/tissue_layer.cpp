#include "materials/tissue_layer.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

std::string_view to_string(CrossingScattering kind) {
    switch (kind) {
        case CrossingScattering::measured_stratum_corneum: return "measured_stratum_corneum";
        case CrossingScattering::measured_epidermis: return "measured_epidermis";
        case CrossingScattering::rayleigh_cosine: return "rayleigh_cosine";
        case CrossingScattering::cosine: return "cosine";
        case CrossingScattering::henyey_greenstein: return "henyey_greenstein";
    }
    return "?";
}

CrossingScattering parse_crossing_scattering(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what,
                       std::array{CrossingScattering::measured_stratum_corneum, CrossingScattering::measured_epidermis,
                                  CrossingScattering::rayleigh_cosine, CrossingScattering::cosine,
                                  CrossingScattering::henyey_greenstein},
                       "a scattering description");
}

std::string_view to_string(PhaseFunctionKind kind) {
    switch (kind) {
        case PhaseFunctionKind::henyey_greenstein: return "henyey_greenstein";
        case PhaseFunctionKind::isotropic: return "isotropic";
        case PhaseFunctionKind::rayleigh: return "rayleigh";
        case PhaseFunctionKind::measured_stratum_corneum: return "measured_stratum_corneum";
        case PhaseFunctionKind::measured_epidermis: return "measured_epidermis";
    }
    return "?";
}

bool is_measured(PhaseFunctionKind kind) {
    return kind == PhaseFunctionKind::measured_stratum_corneum || kind == PhaseFunctionKind::measured_epidermis;
}

PhaseFunctionKind parse_phase_function(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what,
                       std::array{PhaseFunctionKind::henyey_greenstein, PhaseFunctionKind::isotropic,
                                  PhaseFunctionKind::rayleigh, PhaseFunctionKind::measured_stratum_corneum,
                                  PhaseFunctionKind::measured_epidermis},
                       "a phase function");
}

std::string_view to_string(VolumetricSource source) {
    return source == VolumetricSource::power_law ? "power_law" : "from_reduced_scattering";
}

VolumetricSource parse_volumetric_source(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what, std::array{VolumetricSource::power_law, VolumetricSource::from_reduced_scattering}, "a volumetric scattering source");
}

const std::vector<std::string_view>& reduced_scattering_tables() {
    static const std::vector<std::string_view> names{"salomatina_epidermis", "salomatina_dermis", "salomatina_hypodermis"};
    return names;
}

namespace {

enum class Compartment { melanosomes, blood, background, whole_layer };

// One chromophore's share of mu_a inside its compartment (Krishnaswamy & Baranoski 2004; docs/MATERIALS.md, "Layers and stacks"). Adding a
// chromophore is one row here, its data file (materials/chromophore.cpp) and its concentration field
// (materials/material_fields.cpp).
struct AbsorptionTerm {
    Compartment compartment;
    ChromophoreKind chromophore;
    double (*concentration)(const TissueLayer&);           // mg/mL (mass tables), g/L (molar), 1 (absorption)
    double (*molar_mass_g_per_mol)(const ModelOptions&);   // molar tables
    DecadicConversion (*conversion)(const ModelOptions&);  // decadic tables
    bool (*enabled)(const ModelOptions&);
};

// Melanosomes: Sarna & Swartz mass extinction of eu- and pheomelanin; whole blood: haemoglobin split by the
// oxygen saturation S (Prahl) and bilirubin (PhotochemCAD); background: beta-carotene (PhotochemCAD) and
// Jacques' bloodless-tissue baseline; the whole layer: water (Segelstein) and lipid (van Veen).
const std::vector<AbsorptionTerm>& absorption_terms() {
    using L = TissueLayer;
    using M = ModelOptions;
    const auto melanin = [](const M& m) { return m.melanin_tables; };
    const auto molar = [](const M& m) { return m.molar_tables; };
    const auto always = [](const M&) { return true; };
    const auto hemoglobin = [](const M& m) { return m.hemoglobin_molar_mass_g_per_mol; };
    const auto none = [](const M&) { return 1.0; };
    static const std::vector<AbsorptionTerm> terms{
        {Compartment::melanosomes, ChromophoreKind::eumelanin, [](const L& l) { return l.eumelanin_mg_per_ml; }, none, melanin, always},
        {Compartment::melanosomes, ChromophoreKind::pheomelanin, [](const L& l) { return l.pheomelanin_mg_per_ml; }, none, melanin, always},
        {Compartment::blood, ChromophoreKind::oxyhemoglobin, [](const L& l) { return l.oxygen_saturation * l.hemoglobin_g_per_l; },
         hemoglobin, molar, always},
        {Compartment::blood, ChromophoreKind::deoxyhemoglobin, [](const L& l) { return (1.0 - l.oxygen_saturation) * l.hemoglobin_g_per_l; },
         hemoglobin, molar, always},
        {Compartment::blood, ChromophoreKind::bilirubin, [](const L& l) { return l.bilirubin_g_per_l; },
         [](const M& m) { return m.bilirubin_molar_mass_g_per_mol; }, molar, always},
        {Compartment::background, ChromophoreKind::beta_carotene, [](const L& l) { return l.carotene_g_per_l; },
         [](const M& m) { return m.carotene_molar_mass_g_per_mol; }, molar, always},
        {Compartment::background, ChromophoreKind::baseline_tissue, [](const L&) { return 1.0; }, none, molar,
         [](const M& m) { return m.baseline_absorption; }},
        {Compartment::whole_layer, ChromophoreKind::water, [](const L& l) { return l.water_fraction; }, none, molar, always},
        {Compartment::whole_layer, ChromophoreKind::lipid, [](const L& l) { return l.lipid_fraction; }, none, molar, always},
    };
    return terms;
}

// Sum of the compartment's terms [1/cm], as if the compartment filled the volume.
double compartment_absorption_per_cm(Compartment compartment, const TissueLayer& layer, double wavelength_nm, const ModelOptions& model) {
    double mu_a = 0.0;
    for (const auto& term : absorption_terms()) {
        if (term.compartment != compartment || !term.enabled(model)) continue;
        const double c = term.concentration(layer);
        if (c <= 0.0) continue;
        const auto& table = chromophore(term.chromophore);
        const double e = table.table(wavelength_nm);
        switch (table.units) {
            case ExtinctionUnits::mass_per_cm_per_mg_per_ml: mu_a += mu_a_from_mass_extinction_per_cm(e, c, term.conversion(model)); break;
            case ExtinctionUnits::molar_decadic_per_cm_per_molar:
                mu_a += mu_a_from_molar_extinction_per_cm(e, c, term.molar_mass_g_per_mol(model), term.conversion(model));
                break;
            case ExtinctionUnits::absorption_per_cm: mu_a += e * c; break;
        }
    }
    return mu_a;
}

}  // namespace

double absorption_per_cm(const TissueLayer& layer, double wavelength_nm, const ModelOptions& model) {
    const double v_m = layer.melanosome_fraction;
    const double v_b = layer.blood_fraction;
    const double background_fraction = 1.0 - v_m - v_b;
    double mu_a = 0.0;
    if (v_m > 0.0) {
        const double mu_melanosomes = compartment_absorption_per_cm(Compartment::melanosomes, layer, wavelength_nm, model);
        mu_a += v_m * sphere_packaging_factor(mu_melanosomes, layer.melanin_cluster_radius_um) * mu_melanosomes;
    }
    if (v_b > 0.0) {
        const double mu_blood = compartment_absorption_per_cm(Compartment::blood, layer, wavelength_nm, model);
        mu_a += v_b * vessel_packaging_factor(mu_blood, layer.vessel_radius_um) * mu_blood;
    }
    if (background_fraction > 0.0) {
        mu_a += background_fraction * compartment_absorption_per_cm(Compartment::background, layer, wavelength_nm, model);
    }
    mu_a += compartment_absorption_per_cm(Compartment::whole_layer, layer, wavelength_nm, model);
    // Each input is finite and in range, yet their product can overflow (a concentration near 1e308): no solver can use
    // that, and each would say so in its own words (or print inf).
    if (!std::isfinite(mu_a)) {
        throw InputError("layer '" + layer.name + "': its absorbers give mu_a = " + format_number(mu_a) + " /cm at " + format_number(wavelength_nm) +
                         " nm (a concentration or fraction set on it is too large for a finite absorption)");
    }
    return mu_a;
}

double vessel_packaging_factor(double mu_blood_per_cm, double vessel_radius_um) {
    constexpr double cm_per_um = 1e-4;
    const double x = 2.0 * mu_blood_per_cm * vessel_radius_um * cm_per_um;
    return x > 0.0 ? -std::expm1(-x) / x : 1.0;
}

double sphere_packaging_factor(double mu_per_cm, double radius_um) {
    constexpr double cm_per_um = 1e-4;
    const double x = 2.0 * mu_per_cm * radius_um * cm_per_um;
    if (!(x > 0.0)) return 1.0;
    // Below x = 0.01 the closed form loses ~eps/x^2 to cancellation: its series, 1 - 3x/8 + x^2/10 - x^3/48 + x^4/280.
    if (x < 0.01) return 1.0 + x * (-0.375 + x * (0.1 + x * (-1.0 / 48.0 + x / 280.0)));
    const double efficiency = 1.0 - 2.0 * (-std::expm1(-x) - x * std::exp(-x)) / (x * x);
    return 1.5 * efficiency / x;
}

double mie_reduced_scattering_per_cm(const TissueLayer& layer, double wavelength_nm) {
    if (layer.mie_reduced_scattering_per_cm_at_500nm == 0.0) return 0.0;
    return layer.mie_reduced_scattering_per_cm_at_500nm * std::pow(wavelength_nm / 500.0, -layer.mie_reduced_scattering_power);
}

double rayleigh_coefficient_per_cm(const TissueLayer& layer, double wavelength_nm) {
    constexpr double pi = std::numbers::pi;
    constexpr double cm_per_nm = 1e-7;
    const double eta = layer.collagen_fibre_index / layer.refractive_index;
    const double radius_cm = layer.collagen_fibre_radius_nm * cm_per_nm;
    const double n_per_cm3 = layer.collagen_fibre_fraction / (4.0 / 3.0 * pi * radius_cm * radius_cm * radius_cm);
    const double lambda_cm = wavelength_nm * cm_per_nm;
    const double contrast = eta * eta - 1.0;
    if (n_per_cm3 <= 0.0) return 0.0;
    return 8.0 * pi * pi * pi * contrast * contrast / (3.0 * n_per_cm3 * std::pow(lambda_cm, 4));
}

}  // namespace skinspec
