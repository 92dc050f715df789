#pragma once
// The descriptor tables of every field a material file holds (key, unit, range, member, documentation): the
// one place that says what a field is. The TOML reader and writer (materials/material_file.cpp), the range
// checks, `skinspec materials keys`, the --set help and docs/MATERIALS.md (kept in step by a test) all use
// them, so a new chromophore concentration or layer property is one entry here (and, for a chromophore, one
// absorption term in materials/tissue_layer.cpp with its data file).
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "materials/layer_stack.hpp"

namespace skinspec {

struct FieldRange {
    double lo;
    double hi;
    bool lo_open;
    bool hi_open;
    bool contains(double v) const;
    std::string text() const;  // "[0, 1]", "(0, inf)"
};

// Ranges several tables share (materials and the iad setup, inverse/iad/slab_measurement.cpp).
namespace field_ranges {
inline constexpr double inf = std::numeric_limits<double>::infinity();
inline constexpr FieldRange fraction{0.0, 1.0, false, false};
inline constexpr FieldRange positive{0.0, inf, true, true};
inline constexpr FieldRange non_negative{0.0, inf, false, true};
inline constexpr FieldRange refractive_index{1.0, 4.0, false, false};
}  // namespace field_ranges

// The descriptions of a layered skin's scattering a field belongs to (a field without one, e.g. an absorber, a
// thickness or an index, belongs to every description): BioSpec's per-crossing rules (the measured thin-layer
// profiles, Rayleigh and cosine turns, the skin fold), the volumetric description (mu_s and a phase function), and
// the reduced scattering mu_s' of diffusion. A solver reads the ones it declares (SolverCapabilities::descriptions):
// an override of a field it does not read is refused, never silently ignored (solvers/spectral_solver.cpp).
enum class ScatteringDescription { biospec, volumetric, reduced };
std::string_view to_string(ScatteringDescription description);  // what it is, in words, for messages

// A number field of `Owner` (a layer, its optional scattering groups, or the stack).
template <class Owner>
struct NumberField {
    std::string_view key;   // as written in the file, units in the name
    std::string_view unit;
    FieldRange range;
    double Owner::*member;
    bool required;          // must be in the file; otherwise the member's default stands
    std::string_view doc;
    bool absorption_only = false;  // changes mu_a only, never a ray's path (replayable)
    // fit-spectrum's default search range for the field when free (unset: a factor-of-two band around its value).
    std::optional<std::pair<double, double>> fit_bounds = std::nullopt;
    std::optional<ScatteringDescription> description = std::nullopt;  // unset: every description's
    // Read only by a layer whose crossings scatter this way (crossing_in_effect): hg_g with henyey_greenstein, the
    // collagen fibres with rayleigh_cosine. Unset: read whatever the layer's scattering.
    std::optional<CrossingScattering> read_with = std::nullopt;
};

// A [model] switch: a boolean, a decadic-conversion switch (written as true = multiply by ln 10), a number or
// one of a set of names (the Rayleigh turn rule, the fold formula).
struct ModelField {
    std::string_view key;
    std::string_view unit;
    std::variant<bool ModelOptions::*, DecadicConversion ModelOptions::*, double ModelOptions::*, RayleighTurn ModelOptions::*,
                 FoldFormula ModelOptions::*>
        member;
    FieldRange range;  // numbers only
    std::string_view doc;
    bool absorption_only = false;
    std::optional<ScatteringDescription> description = std::nullopt;
};

// A field whose value is one of a set of names (parsed by its own enum parser).
struct NamedField {
    std::string_view section;  // "", "model", "bottom" or "layers"
    std::string_view key;
    std::string_view allowed;
    std::string_view doc;
    std::optional<ScatteringDescription> description = std::nullopt;
};

const std::vector<NumberField<TissueLayer>>& layer_number_fields();
const std::vector<NumberField<VolumetricScattering>>& volumetric_fields();  // present together, mu_s required
const std::vector<NumberField<ReducedScattering>>& reduced_power_law_fields();
const std::vector<NumberField<LayerStack>>& surface_fields();
const std::vector<NumberField<LayerStack>>& bottom_fields();
const std::vector<ModelField>& model_fields();
const std::vector<NamedField>& named_fields();

// Every [model] switch with its value, variant first, in table order: what results (settings) and `materials show`
// report, so that a new switch appears in both with no edit.
using ModelSettingValue = std::variant<bool, double, std::string>;
std::vector<std::pair<std::string, ModelSettingValue>> model_settings(const ModelOptions& model);

// Every key with its section, unit, range or allowed names and documentation, one row each, in file order.
struct FieldRow {
    std::string key;  // "LAYER.melanosome_fraction", "model.dermal_rayleigh", "surface.fold_aspect_ratio", ...
    std::string unit;
    std::string allowed;
    std::string doc;
};
std::vector<FieldRow> material_field_rows();
// The description a key belongs to ("epidermis.hg_g": biospec; "dermis.volumetric_g": volumetric); unset for a
// field of every description or a key that names no field of a layered material.
std::optional<ScatteringDescription> scattering_description(std::string_view key);
// Why the layer field `key` goes unread in a layer it addresses ("layer 'epidermis' scatters by measured_epidermis,
// and hg_g is read only with scattering = henyey_greenstein"); nullopt when every addressed layer reads it or the key
// is no layer field. An override or a free fit parameter it names would be ignored: callers refuse it.
std::optional<std::string> unread_in_layers(const LayerStack& stack, std::string_view key);
// The keys that change absorption only ("LAYER.melanosome_fraction", "model.baseline_absorption", ...).
std::vector<std::string> absorption_only_fields();
// Whether a layer named `layer_name` is addressed by the key head `head` of LAYER.FIELD: its name, or a suffix
// after '_' ("dermis" addresses papillary_dermis and reticular_dermis).
bool layer_matches(std::string_view layer_name, std::string_view head);

// A number field of the layers a key addresses ("epidermis.melanosome_fraction", "dermis.oxygen_saturation"),
// for setting it in place on a stack many times (fits). InputError naming `what`, the key and what is allowed.
struct LayerFieldHandle {
    std::string key;
    const NumberField<TissueLayer>* field = nullptr;
    std::vector<std::size_t> layers;  // indices into the stack
    double get(const LayerStack& stack) const;  // the first addressed layer's value
    void set(LayerStack& stack, double value) const;
};
LayerFieldHandle layer_field(const LayerStack& stack, std::string_view key, std::string_view what);

// The row of a --set key ("epidermis.melanosome_fraction" -> LAYER.melanosome_fraction); nullopt if none.
std::optional<FieldRow> describe_field(std::string_view key);

}  // namespace skinspec
