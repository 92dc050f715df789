#include "materials/tissue_layer.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

template <class Kind, std::size_t N>
Kind parse_named(std::string_view text, std::string_view what, const std::array<Kind, N>& kinds, std::string_view noun) {
    std::string allowed;
    for (const auto k : kinds) {
        if (text == to_string(k)) return k;
        allowed += (allowed.empty() ? "" : ", ") + std::string(to_string(k));
    }
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is not a " + std::string(noun) +
                     " (allowed: " + allowed + ")");
}

double value(ChromophoreKind kind, double wavelength_nm) { return chromophore(kind).table(wavelength_nm); }

}  // namespace

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
    return parse_named(text, what,
                       std::array{CrossingScattering::measured_stratum_corneum, CrossingScattering::measured_epidermis,
                                  CrossingScattering::rayleigh_cosine, CrossingScattering::cosine,
                                  CrossingScattering::henyey_greenstein},
                       "scattering description");
}

std::string_view to_string(PhaseFunctionKind kind) {
    switch (kind) {
        case PhaseFunctionKind::henyey_greenstein: return "henyey_greenstein";
        case PhaseFunctionKind::isotropic: return "isotropic";
        case PhaseFunctionKind::rayleigh: return "rayleigh";
    }
    return "?";
}

PhaseFunctionKind parse_phase_function(std::string_view text, std::string_view what) {
    return parse_named(text, what,
                       std::array{PhaseFunctionKind::henyey_greenstein, PhaseFunctionKind::isotropic,
                                  PhaseFunctionKind::rayleigh},
                       "phase function");
}

const std::vector<std::string_view>& reduced_scattering_tables() {
    static const std::vector<std::string_view> names{"salomatina_epidermis", "salomatina_dermis", "salomatina_hypodermis"};
    return names;
}

double absorption_per_cm(const TissueLayer& layer, double wavelength_nm, const ModelOptions& model) {
    double mu_a = 0.0;
    const double v_m = layer.melanosome_fraction;
    if (v_m > 0.0) {
        // Melanosomes: Sarna & Swartz mass extinction, eumelanin and pheomelanin concentrations inside them.
        mu_a += v_m * (mu_a_from_mass_extinction_per_cm(value(ChromophoreKind::eumelanin, wavelength_nm),
                                                        layer.eumelanin_mg_per_ml, model.melanin_tables) +
                       mu_a_from_mass_extinction_per_cm(value(ChromophoreKind::pheomelanin, wavelength_nm),
                                                        layer.pheomelanin_mg_per_ml, model.melanin_tables));
    }
    const double v_b = layer.blood_fraction;
    if (v_b > 0.0) {
        // Whole blood: haemoglobin split by oxygen saturation S, plus bilirubin (Prahl; PhotochemCAD).
        const double s = layer.oxygen_saturation;
        const double hb = layer.hemoglobin_g_per_l;
        const double m_hb = model.hemoglobin_molar_mass_g_per_mol;
        const double blood =
            mu_a_from_molar_extinction_per_cm(value(ChromophoreKind::oxyhemoglobin, wavelength_nm), s * hb, m_hb,
                                              model.molar_tables) +
            mu_a_from_molar_extinction_per_cm(value(ChromophoreKind::deoxyhemoglobin, wavelength_nm), (1.0 - s) * hb,
                                              m_hb, model.molar_tables) +
            (layer.bilirubin_g_per_l > 0.0
                 ? mu_a_from_molar_extinction_per_cm(value(ChromophoreKind::bilirubin, wavelength_nm),
                                                     layer.bilirubin_g_per_l, model.bilirubin_molar_mass_g_per_mol,
                                                     model.molar_tables)
                 : 0.0);
        mu_a += v_b * blood;
    }
    const double background_fraction = 1.0 - v_m - v_b;
    if (background_fraction > 0.0) {
        double background = 0.0;
        if (layer.carotene_g_per_l > 0.0) {
            background += mu_a_from_molar_extinction_per_cm(value(ChromophoreKind::beta_carotene, wavelength_nm),
                                                            layer.carotene_g_per_l,
                                                            model.carotene_molar_mass_g_per_mol, model.molar_tables);
        }
        if (model.baseline_absorption) background += value(ChromophoreKind::baseline_tissue, wavelength_nm);
        mu_a += background_fraction * background;
    }
    return mu_a;
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
