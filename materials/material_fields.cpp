#include "materials/material_fields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

using field_ranges::fraction, field_ranges::inf, field_ranges::non_negative, field_ranges::positive, field_ranges::refractive_index;
constexpr FieldRange anisotropy{-1.0, 1.0, false, false};
constexpr FieldRange fold_ratio{0.0, 1.0, true, false};
constexpr FieldRange power_law_exponent{-10.0, 10.0, false, false};
constexpr FieldRange vessel_radius{0.0, 1000.0, false, false};

template <class Owner>
void add_rows(std::vector<FieldRow>& rows, const std::string& prefix, const std::vector<NumberField<Owner>>& fields) {
    for (const auto& f : fields) {
        rows.push_back({prefix + std::string(f.key), std::string(f.unit), f.range.text() + (f.required ? ", required" : ""), std::string(f.doc)});
    }
}

}  // namespace

bool FieldRange::contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string FieldRange::text() const {
    const auto bound = [](double b) { return std::isinf(b) ? std::string("inf") : format_number(b); };
    return std::string(lo_open ? "(" : "[") + bound(lo) + ", " + bound(hi) + (hi_open ? ")" : "]");
}

const std::vector<NumberField<TissueLayer>>& layer_number_fields() {
    using L = TissueLayer;
    static const std::vector<NumberField<L>> fields{
        {"thickness_cm", "cm", positive, &L::thickness_cm, true, "layer thickness"},
        {"refractive_index", "1", refractive_index, &L::refractive_index, true, "refractive index of the layer"},
        {"melanosome_fraction", "1", fraction, &L::melanosome_fraction, false, "volume fraction of melanosomes (v_m)", true,
         std::pair{0.001, 0.45}},  // Krishnaswamy & Baranoski 2004: lightly 0.019 ... up to 0.42
        {"eumelanin_mg_per_ml", "mg/mL", non_negative, &L::eumelanin_mg_per_ml, false, "eumelanin inside the melanosomes", true},
        {"pheomelanin_mg_per_ml", "mg/mL", non_negative, &L::pheomelanin_mg_per_ml, false, "pheomelanin inside the melanosomes", true},
        {"blood_fraction", "1", fraction, &L::blood_fraction, false, "volume fraction of whole blood (v_b)", true, std::pair{0.0005, 0.2}},
        {"oxygen_saturation", "1", fraction, &L::oxygen_saturation, false, "haemoglobin oxygen saturation S", true, std::pair{0.0, 1.0}},
        {"hemoglobin_g_per_l", "g/L", non_negative, &L::hemoglobin_g_per_l, false, "haemoglobin in whole blood", true},
        {"bilirubin_g_per_l", "g/L", non_negative, &L::bilirubin_g_per_l, false, "bilirubin in whole blood", true,
         std::pair{0.0, 0.5}},  // normal 0.003-0.012 g/L in serum, jaundice above 0.05
        {"carotene_g_per_l", "g/L", non_negative, &L::carotene_g_per_l, false, "beta-carotene in the background tissue", true,
         std::pair{0.0, 2e-3}},  // ~10x the spec's 2.1e-4 g/L
        {"vessel_radius_um", "um", vessel_radius, &L::vessel_radius_um, false,
         "mean blood-vessel radius for the packaging correction (0: off, blood spread evenly)", true, std::pair{0.0, 100.0}},
        {"melanin_cluster_radius_um", "um", vessel_radius, &L::melanin_cluster_radius_um, false,
         "radius of the spheres packing the melanosomes, for the sieve effect (0: off, melanin spread evenly)", true,
         std::pair{0.0, 5.0}},  // one melanosome 0.1-0.3 um; melanosome complexes and melanocyte dendrites 1-3 um
        {"water_fraction", "1", fraction, &L::water_fraction, false, "volume fraction of water in the layer, blood's included (v_w)", true,
         std::pair{0.05, 0.9}},  // SC 0.15-0.35 ... dermis 0.6-0.7 (docs/HYPERSPECTRAL.md)
        {"lipid_fraction", "1", fraction, &L::lipid_fraction, false,
         "volume fraction of lipid in the layer (v_l; its table covers 429-1098 nm only)", true, std::pair{0.0, 0.3}},
        {"hg_g", "1", anisotropy, &L::hg_g, false, "HG asymmetry for scattering = henyey_greenstein", false, std::nullopt, ScatteringDescription::biospec,
         CrossingScattering::henyey_greenstein},
        {"collagen_fibre_fraction", "1", fraction, &L::collagen_fibre_fraction, false, "collagen volume fraction (Rayleigh, dermal layers)", false,
         std::nullopt, ScatteringDescription::biospec, CrossingScattering::rayleigh_cosine},
        {"collagen_fibre_radius_nm", "nm", positive, &L::collagen_fibre_radius_nm, false, "collagen fibre radius", false, std::nullopt,
         ScatteringDescription::biospec, CrossingScattering::rayleigh_cosine},
        {"collagen_fibre_index", "1", refractive_index, &L::collagen_fibre_index, false, "collagen fibre refractive index", false, std::nullopt,
         ScatteringDescription::biospec, CrossingScattering::rayleigh_cosine},
        {"mie_reduced_scattering_per_cm_at_500nm", "1/cm", non_negative, &L::mie_reduced_scattering_per_cm_at_500nm, false,
         "dermal layers: reduced scattering beyond the Rayleigh regime at 500 nm, a in a (l / 500 nm)^-b, added to the turn test (0: BioSpec, Rayleigh only)",
         false, std::nullopt, ScatteringDescription::biospec, CrossingScattering::rayleigh_cosine},
        {"mie_reduced_scattering_power", "1", power_law_exponent, &L::mie_reduced_scattering_power, false,
         "dermal layers: power-law exponent b of the Mie reduced scattering", false, std::nullopt, ScatteringDescription::biospec,
         CrossingScattering::rayleigh_cosine},
    };
    return fields;
}

const std::vector<NumberField<VolumetricScattering>>& volumetric_fields() {
    using V = VolumetricScattering;
    static const std::vector<NumberField<V>> fields{
        {"volumetric_mu_s_per_cm_at_500nm", "1/cm", non_negative, &V::mu_s_per_cm_at_500nm, true,
         "volumetric walk: scattering coefficient at 500 nm, mu_s(l) = mu_s(500) (l / 500 nm)^-power", false, std::nullopt, ScatteringDescription::volumetric},
        {"volumetric_mu_s_power", "1", power_law_exponent, &V::power, false, "volumetric walk: power-law exponent of mu_s", false, std::nullopt, ScatteringDescription::volumetric},
        {"volumetric_g", "1", anisotropy, &V::g, false,
         "volumetric solvers: HG asymmetry (not with a measured volumetric_phase; below 1 with volumetric_scattering = from_reduced_scattering)", false,
         std::nullopt, ScatteringDescription::volumetric},
    };
    return fields;
}

const std::vector<NumberField<ReducedScattering>>& reduced_power_law_fields() {
    using R = ReducedScattering;
    static const std::vector<NumberField<R>> fields{
        {"reduced_scattering_per_cm_at_500nm", "1/cm", non_negative, &R::per_cm_at_500nm, true,
         "diffusion: reduced scattering at 500 nm, mu_s'(l) = a (l / 500 nm)^-b", false, std::nullopt, ScatteringDescription::reduced},
        {"reduced_scattering_power", "1", power_law_exponent, &R::power, false, "diffusion: power-law exponent b", false, std::nullopt, ScatteringDescription::reduced},
    };
    return fields;
}

const std::vector<NumberField<LayerStack>>& surface_fields() {
    static const std::vector<NumberField<LayerStack>> fields{
        {"above_refractive_index", "1", refractive_index, &LayerStack::above_refractive_index, false, "medium above the skin"},
        {"fold_aspect_ratio", "1", fold_ratio, &LayerStack::fold_aspect_ratio, false, "skin-fold perturbation of surface reflection (sigma)", false,
         std::nullopt, ScatteringDescription::biospec},
    };
    return fields;
}

const std::vector<NumberField<LayerStack>>& bottom_fields() {
    static const std::vector<NumberField<LayerStack>> fields{
        {"below_refractive_index", "1", refractive_index, &LayerStack::below_refractive_index, false, "medium below, for boundary = exit"},
    };
    return fields;
}

const std::vector<ModelField>& model_fields() {
    using M = ModelOptions;
    static const std::vector<ModelField> fields{
        {"dermal_rayleigh", "", &M::dermal_rayleigh, {}, "Rayleigh scattering by collagen in dermal layers", false, ScatteringDescription::biospec},
        {"ln10_molar_tables", "", &M::molar_tables, {}, "multiply decadic molar tables (haemoglobin, bilirubin, carotene) by ln 10", true},
        {"ln10_melanin_tables", "", &M::melanin_tables, {}, "multiply the melanin tables by ln 10", true},
        {"baseline_absorption", "", &M::baseline_absorption, {}, "Jacques' bloodless-tissue absorption in the background", true},
        {"hemoglobin_molar_mass_g_per_mol", "g/mol", &M::hemoglobin_molar_mass_g_per_mol, positive, "haemoglobin molar mass", true},
        {"bilirubin_molar_mass_g_per_mol", "g/mol", &M::bilirubin_molar_mass_g_per_mol, positive, "bilirubin molar mass", true},
        {"carotene_molar_mass_g_per_mol", "g/mol", &M::carotene_molar_mass_g_per_mol, positive, "beta-carotene molar mass", true},
        {"rayleigh_turn", "", &M::rayleigh_turn, {},
         "where a Rayleigh-scattered ray turns: sampled_depth (free path ~ Exp(beta)), whole_crossing (the 2004 text), "
         "no_absorption (authors' code: upward-turned rays charged nothing in the layer)", false, ScatteringDescription::biospec},
        {"swapped_upward_indices", "", &M::swapped_upward_indices, {},
         "authors' code: upward crossings evaluate the interface with its indices swapped (no TIR at SC -> air)", false, ScatteringDescription::biospec},
        {"bottom_exit_fresnel", "", &M::bottom_exit_fresnel, {}, "Fresnel test where light leaves the bottom (boundary = exit)"},
        {"redraw_reversals_in_stratum_corneum", "", &M::redraw_reversals_in_stratum_corneum, {},
         "re-draw an SC perturbation that reverses the travel sense (false: authors' code, the ray leaves / passes on)", false, ScatteringDescription::biospec},
        {"fold_formula", "", &M::fold_formula, {}, "skin-fold perturbation: biospec_2004 or authors_code", false, ScatteringDescription::biospec},
        {"volumetric_matched_to_biospec", "", &M::volumetric_matched_to_biospec, {},
         "volumetric solvers: solve a description derived from the BioSpec one (SC and epidermis mu_s d = 1 with the crossing's profile; "
         "the dermis's mu_s scaled per wavelength so R_d equals biospec-adding-doubling's) instead of the layers' volumetric fields",
         false, ScatteringDescription::volumetric},
    };
    return fields;
}

const std::vector<NamedField>& named_fields() {
    static const std::vector<NamedField> fields{
        {"", "kind", "layered, homogeneous", "what the file describes (default layered)"},
        {"model", "variant", "biospec, biospec-2004, biospec-authors-code", "model variant; sets every [model] switch not given"},
        {"bottom", "boundary", "diffuse_reflector, hypodermis, exit",
         "BioSpec's ideal hypodermis reflector (R = 1), the measured hypodermis as a reflector (Salomatina 2006, 374-1602 nm; T is what it keeps), or an open bottom"},
        {"layers", "name", "lower-case letters, digits, _", "layer name, unique in the stack"},
        {"layers", "scattering", "measured_stratum_corneum, measured_epidermis, rayleigh_cosine, cosine, henyey_greenstein",
         "BioSpec walk: what a crossing does to a ray's direction", ScatteringDescription::biospec},
        {"layers", "volumetric_phase", "henyey_greenstein, isotropic, rayleigh, measured_stratum_corneum, measured_epidermis",
         "volumetric solvers: phase function (measured_*: the Bruls & van der Leun profile as a tabulated phase function, g its mean cosine)", ScatteringDescription::volumetric},
        {"layers", "volumetric_scattering", "power_law, from_reduced_scattering",
         "volumetric solvers: mu_s from volumetric_mu_s_* (default), or mu_s = mu_s' / (1 - volumetric_g) from the layer's reduced scattering", ScatteringDescription::volumetric},
        {"layers", "reduced_scattering_table", "salomatina_epidermis, salomatina_dermis, salomatina_hypodermis",
         "diffusion: measured reduced scattering (or the power law, not both)", ScatteringDescription::reduced},
    };
    return fields;
}

std::vector<std::pair<std::string, ModelSettingValue>> model_settings(const ModelOptions& model) {
    std::vector<std::pair<std::string, ModelSettingValue>> out{{"variant", model.variant}};
    for (const auto& f : model_fields()) {
        std::visit(
            [&](auto member) {
                using T = std::remove_cvref_t<decltype(model.*member)>;
                if constexpr (std::is_same_v<T, DecadicConversion>) out.emplace_back(f.key, model.*member == DecadicConversion::multiply_ln10);
                else if constexpr (std::is_enum_v<T>) out.emplace_back(f.key, std::string(to_string(model.*member)));
                else out.emplace_back(f.key, model.*member);
            },
            f.member);
    }
    return out;
}

std::vector<FieldRow> material_field_rows() {
    std::vector<FieldRow> rows;
    const auto named = [&](std::string_view section, const std::string& prefix) {
        for (const auto& f : named_fields()) {
            if (f.section == section) rows.push_back({prefix + std::string(f.key), "", std::string(f.allowed), std::string(f.doc)});
        }
    };
    named("", "");
    named("model", "model.");
    for (const auto& f : model_fields()) {
        const std::string allowed = std::visit(
            [&](auto member) -> std::string {
                using T = std::remove_cvref_t<decltype(ModelOptions{}.*member)>;
                if constexpr (std::is_same_v<T, double>) return f.range.text();
                else if constexpr (std::is_same_v<T, RayleighTurn>) return "sampled_depth, whole_crossing, no_absorption";
                else if constexpr (std::is_same_v<T, FoldFormula>) return "biospec_2004, authors_code";
                else return "true, false";
            },
            f.member);
        rows.push_back({"model." + std::string(f.key), std::string(f.unit), allowed, std::string(f.doc)});
    }
    add_rows(rows, "surface.", surface_fields());
    named("bottom", "bottom.");
    add_rows(rows, "bottom.", bottom_fields());
    named("layers", "LAYER.");
    add_rows(rows, "LAYER.", layer_number_fields());
    add_rows(rows, "LAYER.", volumetric_fields());
    add_rows(rows, "LAYER.", reduced_power_law_fields());
    return rows;
}

std::vector<std::string> absorption_only_fields() {
    std::vector<std::string> keys;
    for (const auto& f : layer_number_fields()) {
        if (f.absorption_only) keys.push_back("LAYER." + std::string(f.key));
    }
    for (const auto& f : model_fields()) {
        if (f.absorption_only) keys.push_back("model." + std::string(f.key));
    }
    return keys;
}

std::string_view to_string(ScatteringDescription description) {
    switch (description) {
        case ScatteringDescription::biospec:
            return "the BioSpec description (per-crossing scattering: the measured thin-layer profiles, Rayleigh and cosine turns, the skin fold)";
        case ScatteringDescription::volumetric: return "the volumetric description (mu_s and the phase function)";
        case ScatteringDescription::reduced: return "the reduced scattering mu_s' of diffusion";
    }
    return "";
}

std::optional<std::string> unread_in_layers(const LayerStack& stack, std::string_view key) {
    const auto dot = key.find('.');
    if (dot == std::string_view::npos) return std::nullopt;
    const auto head = key.substr(0, dot), field = key.substr(dot + 1);
    const auto row = std::find_if(layer_number_fields().begin(), layer_number_fields().end(), [&](const auto& f) { return f.key == field; });
    if (row == layer_number_fields().end() || !row->read_with) return std::nullopt;
    for (const auto& layer : stack.layers) {
        if (!layer_matches(layer.name, head)) continue;
        const auto in_effect = crossing_in_effect(layer, stack.model);
        if (in_effect == *row->read_with) continue;
        const bool switched_off = in_effect != layer.crossing;
        return "layer '" + layer.name + "' scatters by " + std::string(to_string(in_effect)) + (switched_off ? " (model.dermal_rayleigh = false)" : "") + ", and " +
               std::string(field) + " is read only with scattering = " + std::string(to_string(*row->read_with));
    }
    return std::nullopt;
}

std::optional<ScatteringDescription> scattering_description(std::string_view key) {
    const auto dot = key.find('.');
    if (dot == std::string_view::npos) return std::nullopt;
    const auto section = key.substr(0, dot), field = key.substr(dot + 1);
    const auto in = [&](const auto& table) -> std::optional<std::optional<ScatteringDescription>> {
        for (const auto& f : table) {
            if (f.key == field) return f.description;
        }
        return std::nullopt;
    };
    std::optional<std::optional<ScatteringDescription>> found;
    if (section == "model") {
        found = in(model_fields());
    } else if (section == "surface") {
        found = in(surface_fields());
    } else if (section == "bottom") {
        found = in(bottom_fields());
    } else {
        for (const auto& f : named_fields()) {
            if (f.section == "layers" && f.key == field) found = f.description;
        }
        if (!found) found = in(layer_number_fields());
        if (!found) found = in(volumetric_fields());
        if (!found) found = in(reduced_power_law_fields());
    }
    return found ? *found : std::nullopt;
}

bool layer_matches(std::string_view layer_name, std::string_view head) {
    return layer_name == head || (layer_name.size() > head.size() + 1 && layer_name.ends_with(head) &&
                                  layer_name[layer_name.size() - head.size() - 1] == '_');
}

double LayerFieldHandle::get(const LayerStack& stack) const { return stack.layers[layers.front()].*(field->member); }

void LayerFieldHandle::set(LayerStack& stack, double value) const {
    for (const auto k : layers) stack.layers[k].*(field->member) = value;
}

LayerFieldHandle layer_field(const LayerStack& stack, std::string_view key, std::string_view what) {
    const auto dot = key.find('.');
    if (dot == std::string_view::npos || dot == 0 || dot + 1 == key.size()) {
        throw InputError(std::string(what) + " '" + std::string(key) + "': must be LAYER.FIELD (e.g. epidermis.melanosome_fraction)");
    }
    const auto head = key.substr(0, dot);
    const auto name = key.substr(dot + 1);
    LayerFieldHandle handle{std::string(key), nullptr, {}};
    std::string fields;
    for (const auto& f : layer_number_fields()) {
        if (f.key == name) handle.field = &f;
        fields += (fields.empty() ? "" : ", ") + std::string(f.key);
    }
    if (!handle.field) {
        throw InputError(std::string(what) + " '" + std::string(key) + "': '" + std::string(name) + "' is not a layer field (allowed: " + fields + ")");
    }
    std::string layers;
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        if (layer_matches(stack.layers[k].name, head)) handle.layers.push_back(k);
        layers += (layers.empty() ? "" : ", ") + stack.layers[k].name;
    }
    if (handle.layers.empty()) {
        throw InputError(std::string(what) + " '" + std::string(key) + "': no layer '" + std::string(head) + "' in '" + stack.name +
                         "' (layers: " + layers + ")");
    }
    return handle;
}

std::optional<FieldRow> describe_field(std::string_view key) {
    const auto dot = key.find('.');
    std::string wanted(key);
    if (dot != std::string_view::npos) {
        const auto section = key.substr(0, dot);
        if (section != "model" && section != "surface" && section != "bottom") wanted = "LAYER." + std::string(key.substr(dot + 1));
    }
    for (auto& row : material_field_rows()) {
        if (row.key == wanted) return row;
    }
    return std::nullopt;
}

}  // namespace skinspec
