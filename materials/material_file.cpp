#include "materials/material_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "materials/material_fields.hpp"
#include "materials/parameter_sweep.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

using Range = FieldRange;
constexpr Range fraction{0.0, 1.0, false, false};
constexpr Range non_negative{0.0, std::numeric_limits<double>::infinity(), false, true};

// Reads typed, range-checked values out of a toml table and reports where a bad one came from.
class Reader {
public:
    Reader(std::string file, std::map<std::string, std::string> overridden) : file_(std::move(file)), overridden_(std::move(overridden)) {}

    std::string where(const toml::node* node, const std::string& path) const {
        if (const auto it = overridden_.find(path); it != overridden_.end()) return file_ + " (" + it->second + " " + path + "): ";
        if (node && node->source().begin.line > 0) {
            return file_ + ":" + std::to_string(node->source().begin.line) + ": ";
        }
        return file_ + ": ";
    }

    void reject_unknown(const toml::table& table, const std::string& prefix, const std::vector<std::string_view>& known) const {
        for (const auto& [key, node] : table) {
            if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
            std::string allowed;
            for (const auto k : known) allowed += (allowed.empty() ? "" : ", ") + std::string(k);
            throw InputError(where(&node, prefix + std::string(key.str())) + "unknown key '" + prefix +
                             std::string(key.str()) + "' (allowed: " + allowed + ")");
        }
    }

    const toml::node* require(const toml::table& table, std::string_view key, const std::string& path) const {
        const auto* node = table.get(key);
        if (!node) throw InputError(where(&table, path) + "key '" + path + "' is missing");
        return node;
    }

    double number(const toml::table& table, std::string_view key, const std::string& path, Range range,
                  std::optional<double> fallback) const {
        const auto* node = fallback ? table.get(key) : require(table, key, path);
        if (!node) return *fallback;
        const auto value = node->value<double>();
        if (!value) throw InputError(where(node, path) + "key '" + path + "' must be a number in " + range.text());
        if (!range.contains(*value)) {
            throw InputError(where(node, path) + "key '" + path + "' = " + format_number(*value) + " is outside " + range.text());
        }
        return *value;
    }

    std::string string(const toml::table& table, std::string_view key, const std::string& path,
                       std::optional<std::string> fallback) const {
        const auto* node = fallback ? table.get(key) : require(table, key, path);
        if (!node) return *fallback;
        const auto value = node->value<std::string>();
        if (!value) throw InputError(where(node, path) + "key '" + path + "' must be a string");
        return *value;
    }

    bool boolean(const toml::table& table, std::string_view key, const std::string& path, bool fallback) const {
        const auto* node = table.get(key);
        if (!node) return fallback;
        const auto value = node->value<bool>();
        if (!value) throw InputError(where(node, path) + "key '" + path + "' must be true or false");
        return *value;
    }

    std::vector<double> numbers(const toml::table& table, std::string_view key, const std::string& path, Range range,
                                bool required) const {
        const auto* node = required ? require(table, key, path) : table.get(key);
        std::vector<double> out;
        if (!node) return out;
        const auto* array = node->as_array();
        if (!array) throw InputError(where(node, path) + "key '" + path + "' must be an array of numbers in " + range.text());
        for (const auto& element : *array) {
            const auto value = element.value<double>();
            if (!value || !range.contains(*value)) {
                throw InputError(where(node, path) + "key '" + path + "' has an entry outside " + range.text());
            }
            out.push_back(*value);
        }
        return out;
    }

    const toml::table* section(const toml::table& table, std::string_view key, const std::string& path) const {
        const auto* node = table.get(key);
        if (!node) return nullptr;
        if (!node->as_table()) throw InputError(where(node, path) + "'" + path + "' must be a table ([" + path + "])");
        return node->as_table();
    }

private:
    std::string file_;
    std::map<std::string, std::string> overridden_;  // key path -> the option that set it
};

bool valid_layer_name(const std::string& name) {
    return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    });
}

template <class Owner>
std::vector<std::string_view> keys_of(const std::vector<NumberField<Owner>>& fields) {
    std::vector<std::string_view> keys;
    for (const auto& f : fields) keys.push_back(f.key);
    return keys;
}

// Reads every number field of `fields` into `owner` (defaults: the member's current value).
template <class Owner>
void read_numbers(const Reader& r, const toml::table& t, const std::string& prefix, const std::vector<NumberField<Owner>>& fields, Owner& owner) {
    for (const auto& f : fields) {
        owner.*f.member = r.number(t, f.key, prefix + std::string(f.key), f.range,
                                   f.required ? std::nullopt : std::optional<double>(owner.*f.member));
    }
}

template <class Owner>
void write_numbers(toml::table& t, const std::vector<NumberField<Owner>>& fields, const Owner& owner) {
    for (const auto& f : fields) t.insert(f.key, owner.*f.member);
}

ModelOptions read_model(const Reader& r, const toml::table* model) {
    if (!model) return ModelOptions{};
    std::vector<std::string_view> known{"variant"};
    for (const auto& f : model_fields()) known.push_back(f.key);
    r.reject_unknown(*model, "model.", known);
    const auto variant_name = r.string(*model, "variant", "model.variant", std::string("biospec"));
    ModelOptions o = model_variant(variant_name, r.where(model->get("variant"), "model.variant") + "key 'model.variant'");
    const auto ln10 = [](bool on) { return on ? DecadicConversion::multiply_ln10 : DecadicConversion::omit_ln10; };
    for (const auto& f : model_fields()) {
        const std::string path = "model." + std::string(f.key);
        std::visit([&](auto member) {
            using T = std::remove_cvref_t<decltype(o.*member)>;
            if constexpr (std::is_same_v<T, bool>) o.*member = r.boolean(*model, f.key, path, o.*member);
            else if constexpr (std::is_same_v<T, DecadicConversion>) o.*member = ln10(r.boolean(*model, f.key, path, o.*member == DecadicConversion::multiply_ln10));
            else if constexpr (std::is_same_v<T, double>) o.*member = r.number(*model, f.key, path, f.range, o.*member);
            else if constexpr (std::is_same_v<T, RayleighTurn>) {
                o.*member = parse_rayleigh_turn(r.string(*model, f.key, path, std::string(to_string(o.*member))),
                                                r.where(model->get(f.key), path) + "key '" + path + "'");
            } else {
                o.*member = parse_fold_formula(r.string(*model, f.key, path, std::string(to_string(o.*member))),
                                               r.where(model->get(f.key), path) + "key '" + path + "'");
            }
        }, f.member);
    }
    return o;
}

TissueLayer read_layer(const Reader& r, const toml::table& t, std::size_t index) {
    TissueLayer layer;
    const std::string fallback_path = "layers[" + std::to_string(index) + "].";
    layer.name = r.string(t, "name", fallback_path + "name", std::nullopt);
    if (!valid_layer_name(layer.name)) {
        throw InputError(r.where(t.get("name"), fallback_path + "name") + "layer name '" + layer.name +
                         "' is not allowed (allowed: lower-case letters, digits and _)");
    }
    const std::string p = layer.name + ".";
    std::vector<std::string_view> known{"name"};
    for (const auto& keys : {keys_of(layer_number_fields()), std::vector<std::string_view>{"scattering"}, keys_of(volumetric_fields()),
                             std::vector<std::string_view>{"volumetric_phase", "volumetric_scattering", "reduced_scattering_table"},
                             keys_of(reduced_power_law_fields())}) {
        known.insert(known.end(), keys.begin(), keys.end());
    }
    r.reject_unknown(t, p, known);
    read_numbers(r, t, p, layer_number_fields(), layer);
    if (layer.melanosome_fraction + layer.blood_fraction > 1.0) {
        throw InputError(r.where(t.get("blood_fraction"), p + "blood_fraction") + "layer '" + layer.name +
                         "': melanosome_fraction + blood_fraction = " +
                         format_number(layer.melanosome_fraction + layer.blood_fraction) + " is outside [0, 1]");
    }
    layer.crossing = parse_crossing_scattering(r.string(t, "scattering", p + "scattering", std::nullopt),
                                               r.where(t.get("scattering"), p + "scattering") + "key '" + p + "scattering'");
    const bool volumetric = std::any_of(volumetric_fields().begin(), volumetric_fields().end(), [&](const auto& f) { return t.contains(f.key); }) ||
                            t.contains("volumetric_phase") || t.contains("volumetric_scattering");
    const bool has_table = t.contains("reduced_scattering_table");
    const bool has_law = std::any_of(reduced_power_law_fields().begin(), reduced_power_law_fields().end(),
                                     [&](const auto& f) { return t.contains(f.key); });
    if (has_table && has_law) {
        throw InputError(r.where(t.get("reduced_scattering_table"), p + "reduced_scattering_table") + "layer '" +
                         layer.name + "': give reduced_scattering_table or the power law, not both");
    }
    if (volumetric) {
        VolumetricScattering v;
        v.phase = parse_phase_function(r.string(t, "volumetric_phase", p + "volumetric_phase", "henyey_greenstein"),
                                       r.where(t.get("volumetric_phase"), p + "volumetric_phase") + "key '" + p +
                                           "volumetric_phase'");
        if (is_measured(v.phase) && t.contains("volumetric_g")) {
            throw InputError(r.where(t.get("volumetric_g"), p + "volumetric_g") + "layer '" + layer.name + "': volumetric_g contradicts volumetric_phase = " +
                             std::string(to_string(v.phase)) + " (g is the measured profile's mean cosine)");
        }
        const std::string source_key = p + "volumetric_scattering";
        v.source = parse_volumetric_source(r.string(t, "volumetric_scattering", source_key, "power_law"),
                                           r.where(t.get("volumetric_scattering"), source_key) + "key '" + source_key + "'");
        if (v.source == VolumetricSource::power_law) {
            read_numbers(r, t, p, volumetric_fields(), v);
        } else {
            for (const auto& f : volumetric_fields()) {
                if (f.key != "volumetric_g" && t.contains(f.key)) {
                    throw InputError(r.where(t.get(f.key), p + std::string(f.key)) + "layer '" + layer.name + "': " + std::string(f.key) +
                                     " contradicts volumetric_scattering = from_reduced_scattering (mu_s comes from mu_s' / (1 - g))");
                }
            }
            if (!has_table && !has_law) {
                throw InputError(r.where(t.get("volumetric_scattering"), source_key) + "layer '" + layer.name +
                                 "': volumetric_scattering = from_reduced_scattering needs reduced_scattering_table or the reduced power law");
            }
            v.g = r.number(t, "volumetric_g", p + "volumetric_g", FieldRange{-1.0, 1.0, false, false}, 0.0);
            if (v.g == 1.0) {
                throw InputError(r.where(t.get("volumetric_g"), p + "volumetric_g") + "key '" + p + "volumetric_g' = 1 is outside [-1, 1) with "
                                 "volumetric_scattering = from_reduced_scattering (mu_s = mu_s' / (1 - g) would be infinite)");
            }
        }
        layer.volumetric = v;
    }
    if (has_table) {
        ReducedScattering reduced;
        reduced.table = r.string(t, "reduced_scattering_table", p + "reduced_scattering_table", std::nullopt);
        const auto& known = reduced_scattering_tables();
        if (std::find(known.begin(), known.end(), reduced.table) == known.end()) {
            throw InputError(r.where(t.get("reduced_scattering_table"), p + "reduced_scattering_table") + "key '" + p +
                             "reduced_scattering_table' = '" + reduced.table +
                             "' is not a table (allowed: salomatina_epidermis, salomatina_dermis, salomatina_hypodermis)");
        }
        layer.reduced = reduced;
    } else if (has_law) {
        ReducedScattering reduced;
        read_numbers(r, t, p, reduced_power_law_fields(), reduced);
        layer.reduced = reduced;
    }
    return layer;
}

LayerStack read_stack(const Reader& r, const toml::table& root) {
    r.reject_unknown(root, "", {"kind", "name", "description", "model", "surface", "bottom", "layers"});
    LayerStack stack;
    stack.name = r.string(root, "name", "name", std::nullopt);
    stack.description = r.string(root, "description", "description", std::string());
    stack.model = read_model(r, r.section(root, "model", "model"));
    if (const auto* surface = r.section(root, "surface", "surface")) {
        r.reject_unknown(*surface, "surface.", keys_of(surface_fields()));
        read_numbers(r, *surface, "surface.", surface_fields(), stack);
    }
    if (const auto* bottom = r.section(root, "bottom", "bottom")) {
        auto known = keys_of(bottom_fields());
        known.push_back("boundary");
        r.reject_unknown(*bottom, "bottom.", known);
        stack.bottom = parse_bottom_boundary(r.string(*bottom, "boundary", "bottom.boundary", "diffuse_reflector"),
                                             r.where(bottom->get("boundary"), "bottom.boundary") + "key 'bottom.boundary'");
        read_numbers(r, *bottom, "bottom.", bottom_fields(), stack);
    }
    const auto* layers = root.get("layers");
    if (!layers || !layers->as_array() || layers->as_array()->empty()) {
        throw InputError(r.where(layers, "layers") + "a layered material needs at least one [[layers]] table");
    }
    std::size_t index = 0;
    for (const auto& node : *layers->as_array()) {
        const auto* table = node.as_table();
        if (!table) throw InputError(r.where(&node, "layers") + "every entry of 'layers' must be a table ([[layers]])");
        auto layer = read_layer(r, *table, index++);
        for (const auto& other : stack.layers) {
            if (other.name == layer.name) {
                throw InputError(r.where(table->get("name"), layer.name + ".name") + "layer name '" + layer.name + "' is used twice");
            }
        }
        stack.layers.push_back(std::move(layer));
    }
    return stack;
}

HomogeneousMaterial read_homogeneous(const Reader& r, const toml::table& root) {
    r.reject_unknown(root, "", {"kind", "name", "description", "relative_refractive_index", "bands",
                                "reduced_scattering_per_mm", "absorption_per_mm", "published_diffuse_reflectance"});
    HomogeneousMaterial m;
    m.name = r.string(root, "name", "name", std::nullopt);
    m.description = r.string(root, "description", "description", std::string());
    m.relative_refractive_index = r.number(root, "relative_refractive_index", "relative_refractive_index",
                                           Range{0.2, 5.0, false, false}, std::nullopt);
    const auto* bands = r.require(root, "bands", "bands");
    if (!bands->as_array()) throw InputError(r.where(bands, "bands") + "key 'bands' must be an array of names");
    for (const auto& b : *bands->as_array()) {
        const auto name = b.value<std::string>();
        if (!name) throw InputError(r.where(bands, "bands") + "key 'bands' must be an array of names");
        m.bands.push_back(*name);
    }
    m.reduced_scattering_per_mm = r.numbers(root, "reduced_scattering_per_mm", "reduced_scattering_per_mm", non_negative, true);
    m.absorption_per_mm = r.numbers(root, "absorption_per_mm", "absorption_per_mm", non_negative, true);
    m.published_diffuse_reflectance =
        r.numbers(root, "published_diffuse_reflectance", "published_diffuse_reflectance", fraction, false);
    const auto n = m.bands.size();
    if (n == 0 || m.reduced_scattering_per_mm.size() != n || m.absorption_per_mm.size() != n ||
        (!m.published_diffuse_reflectance.empty() && m.published_diffuse_reflectance.size() != n)) {
        throw InputError(r.where(bands, "bands") + "bands, reduced_scattering_per_mm, absorption_per_mm (and "
                         "published_diffuse_reflectance) must have the same, non-zero length");
    }
    return m;
}

InputError unknown_section(const std::string& what, const std::string& head, const std::vector<std::string>& layer_names) {
    std::string allowed = "model, surface, bottom";
    for (const auto& n : layer_names) allowed += ", " + n;
    return InputError(what + ": no layer or section '" + head + "' (allowed: " + allowed + ")");
}

// Parses "--set" value text as a TOML value (held in a one-key table under "v"); text that is not one is a string.
toml::table override_value(const std::string& text) {
    try {
        return toml::parse("v = " + text);
    } catch (const toml::parse_error&) {
        return toml::table{{"v", text}};
    }
}

// Applies overrides to the parsed document; returns the set of overridden key paths (for messages).
std::map<std::string, std::string> apply_overrides(toml::table& root, const std::vector<MaterialOverride>& overrides) {
    std::map<std::string, std::string> paths;
    for (const auto& o : overrides) {
        const auto dot = o.key.find('.');
        auto set = [&](toml::table& table, const std::string& key, const std::string& path) {
            auto value = override_value(o.value);
            table.insert_or_assign(key, std::move(*value.get("v")));
            paths[path] = o.origin;
        };
        if (dot == std::string::npos) {
            set(root, o.key, o.key);
            continue;
        }
        const std::string head = o.key.substr(0, dot);
        const std::string key = o.key.substr(dot + 1);
        if (key.empty() || key.find('.') != std::string::npos) {
            throw InputError(o.origin + " " + o.key + ": key must be NAME or SECTION.NAME (e.g. epidermis.melanosome_fraction)");
        }
        if (head == "model" || head == "surface" || head == "bottom") {
            if (!root.contains(head)) root.insert(head, toml::table{});
            if (auto* section = root.get(head)->as_table()) {
                set(*section, key, o.key);
                continue;
            }
        }
        std::vector<std::string> names;
        bool matched = false;
        if (auto* layers = root.get("layers"); layers && layers->as_array()) {
            for (auto& node : *layers->as_array()) {
                auto* layer = node.as_table();
                if (!layer) continue;
                const auto name = (*layer)["name"].value_or(std::string());
                names.push_back(name);
                if (layer_matches(name, head)) {
                    set(*layer, key, name + "." + key);
                    matched = true;
                }
            }
        }
        if (!matched) throw unknown_section(o.origin + " " + o.key, head, names);
    }
    return paths;
}

toml::array array_of(const std::vector<double>& values) {
    toml::array out;
    for (const double v : values) out.push_back(v);
    return out;
}

// With `every_model_switch` false, the variant and only the switches that differ from it (what a file holds, so
// that a later --variant still takes effect); with true, every switch's value (what material_field reads).
toml::table stack_table(const LayerStack& s, bool every_model_switch) {
    toml::table root{{"kind", "layered"}, {"name", s.name}, {"description", s.description}};
    const auto defaults = model_variant(s.model.variant, "model.variant");
    toml::table model{{"variant", s.model.variant}};
    for (const auto& f : model_fields()) {
        std::visit([&](auto member) {
            using T = std::remove_cvref_t<decltype(s.model.*member)>;
            if (!every_model_switch && s.model.*member == defaults.*member) return;
            if constexpr (std::is_same_v<T, DecadicConversion>) model.insert(f.key, s.model.*member == DecadicConversion::multiply_ln10);
            else if constexpr (std::is_enum_v<T>) model.insert(f.key, std::string(to_string(s.model.*member)));
            else model.insert(f.key, s.model.*member);
        }, f.member);
    }
    root.insert("model", std::move(model));
    toml::table surface, bottom{{"boundary", std::string(to_string(s.bottom))}};
    write_numbers(surface, surface_fields(), s);
    write_numbers(bottom, bottom_fields(), s);
    root.insert("surface", std::move(surface));
    root.insert("bottom", std::move(bottom));
    toml::array layers;
    for (const auto& l : s.layers) {
        toml::table t{{"name", l.name}, {"scattering", std::string(to_string(l.crossing))}};
        write_numbers(t, layer_number_fields(), l);
        if (l.volumetric) {
            if (l.volumetric->source == VolumetricSource::power_law) {
                write_numbers(t, volumetric_fields(), *l.volumetric);
            } else {
                t.insert("volumetric_scattering", std::string(to_string(l.volumetric->source)));
                t.insert("volumetric_g", l.volumetric->g);
            }
            if (is_measured(l.volumetric->phase)) t.erase("volumetric_g");
            t.insert("volumetric_phase", std::string(to_string(l.volumetric->phase)));
        }
        if (l.reduced && !l.reduced->table.empty()) t.insert("reduced_scattering_table", l.reduced->table);
        if (l.reduced && l.reduced->table.empty()) write_numbers(t, reduced_power_law_fields(), *l.reduced);
        layers.push_back(std::move(t));
    }
    root.insert("layers", std::move(layers));
    return root;
}

toml::table homogeneous_table(const HomogeneousMaterial& m) {
    toml::array bands;
    for (const auto& b : m.bands) bands.push_back(b);
    toml::table root{{"kind", "homogeneous"},
                     {"name", m.name},
                     {"description", m.description},
                     {"relative_refractive_index", m.relative_refractive_index}};
    root.insert("bands", std::move(bands));
    root.insert("reduced_scattering_per_mm", array_of(m.reduced_scattering_per_mm));
    root.insert("absorption_per_mm", array_of(m.absorption_per_mm));
    if (!m.published_diffuse_reflectance.empty()) {
        root.insert("published_diffuse_reflectance", array_of(m.published_diffuse_reflectance));
    }
    return root;
}

}  // namespace

namespace {

constexpr std::array<std::pair<std::string_view, BottomBoundary>, 3> reflector_values{
    {{"on", BottomBoundary::diffuse_reflector}, {"off", BottomBoundary::exit}, {"hypodermis", BottomBoundary::hypodermis}}};

}  // namespace

std::string reflector_choices() {
    std::string out;
    for (const auto& [name, bottom] : reflector_values) out += (out.empty() ? "" : ", ") + std::string(name);
    return out;
}

MaterialOverride reflector_override(std::string_view value, const std::string& origin) {
    for (const auto& [name, bottom] : reflector_values) {
        if (value == name) return {"bottom.boundary", std::string(to_string(bottom)), origin};
    }
    throw InputError(origin + ": '" + std::string(value) + "' is not allowed (allowed: " + reflector_choices() + ")");
}

MaterialOverride parse_override(std::string_view text) {
    const auto eq = text.find('=');
    if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size()) {
        throw InputError("--set '" + std::string(text) + "' must have the form KEY=VALUE (e.g. epidermis.melanosome_fraction=0.1)");
    }
    return {std::string(trim(text.substr(0, eq))), std::string(trim(text.substr(eq + 1)))};
}

Material read_material(const std::filesystem::path& file, const std::vector<MaterialOverride>& overrides) {
    const std::string name = file.string();
    auto in = open_input_file(file, "material file");
    std::ostringstream text;
    text << in.rdbuf();
    if (!in && !in.eof()) throw InputError(name + ": cannot read the material file");
    return parse_material(text.str(), name, overrides);
}

Material parse_material(std::string_view toml_text, std::string_view source, const std::vector<MaterialOverride>& overrides) {
    const std::string name(source);
    toml::table root;
    try {
        root = toml::parse(toml_text, name);
    } catch (const toml::parse_error& e) {
        throw InputError(name + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column) +
                         ": TOML syntax error: " + std::string(e.description()));
    }
    const Reader reader(name, apply_overrides(root, overrides));
    const auto kind = reader.string(root, "kind", "kind", std::string("layered"));
    if (kind == "layered") return read_stack(reader, root);
    if (kind == "homogeneous") return read_homogeneous(reader, root);
    throw InputError(reader.where(root.get("kind"), "kind") + "key 'kind' = '" + kind + "' is not allowed (allowed: layered, homogeneous)");
}

std::vector<std::filesystem::path> preset_files() {
    std::vector<std::filesystem::path> files;
    const auto folder = data_directory() / "materials";
    if (!std::filesystem::is_directory(folder)) throw InputError("preset folder " + folder.string() + " not found");
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        if (entry.is_regular_file() && entry.path().extension() == ".toml") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

Material load_material(std::string_view name_or_file, const std::vector<MaterialOverride>& overrides) {
    const std::filesystem::path as_path(name_or_file);
    if (as_path.extension() == ".toml" || name_or_file.find('/') != std::string_view::npos) {
        return read_material(as_path, overrides);
    }
    std::string allowed;
    for (const auto& file : preset_files()) {
        if (file.stem() == name_or_file) return read_material(file, overrides);
        allowed += (allowed.empty() ? "" : ", ") + file.stem().string();
    }
    throw InputError("material '" + std::string(name_or_file) + "' is neither a preset nor a .toml file (presets: " + allowed + ")");
}

const std::string& material_name(const Material& material) {
    return std::visit([](const auto& m) -> const std::string& { return m.name; }, material);
}

const std::string& material_description(const Material& material) {
    return std::visit([](const auto& m) -> const std::string& { return m.description; }, material);
}

Material relabelled(Material material, std::string name, const std::vector<MaterialOverride>& changes) {
    std::visit(
        [&](auto& m) {
            std::string changed;
            for (const auto& c : changes) changed += (changed.empty() ? "" : ", ") + c.key + "=" + c.value;
            if (!changed.empty()) m.description += (m.description.empty() ? "" : "; ") + std::string("changed from ") + m.name + ": " + changed;
            m.name = std::move(name);
        },
        material);
    return material;
}

namespace {

// toml++ writes a double with 17 significant digits (0.05 as 0.050000000000000003). Every float literal outside
// strings and comments is rewritten as the shortest decimal that reads back as the same double (format_number), with a
// decimal point kept so that it stays a TOML float.
bool starts_number(const std::string& text, std::size_t i) {
    const auto digit = [](char c) { return c >= '0' && c <= '9'; };
    const auto word = [&](char c) { return digit(c) || std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
    if (i > 0 && word(text[i - 1])) return false;  // a digit inside a bare key (per_cm_at_500nm)
    return digit(text[i]) || ((text[i] == '-' || text[i] == '+') && i + 1 < text.size() && digit(text[i + 1]));
}

std::string shortest_float(const std::string& literal) {
    if (literal.find_first_of(".eE") == std::string::npos || literal.find('_') != std::string::npos) return literal;  // an integer
    double value = 0.0;
    const char* first = literal.data() + (literal.front() == '+' ? 1 : 0);
    const auto [end, error] = std::from_chars(first, literal.data() + literal.size(), value);
    if (error != std::errc() || end != literal.data() + literal.size()) return literal;
    auto text = format_number(value);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text;
}

std::string with_shortest_floats(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    std::size_t i = 0;
    const auto copy_until = [&](std::size_t end) {
        out.append(text, i, end - i);
        i = end;
    };
    while (i < text.size()) {
        const char c = text[i];
        if (c == '#') {
            copy_until(std::min(text.find('\n', i), text.size()));
        } else if (c == '"' || c == '\'') {
            const std::string triple(3, c);
            const bool multi = text.compare(i, 3, triple) == 0;
            std::size_t end = i + (multi ? 3 : 1);
            while (end < text.size() && text.compare(end, multi ? 3 : 1, multi ? triple : std::string(1, c)) != 0) {
                end += (c == '"' && text[end] == '\\') ? 2 : 1;  // a basic string's escape, \" included
            }
            copy_until(std::min(end + (multi ? 3 : 1), text.size()));
        } else if (starts_number(text, i)) {
            std::size_t end = i + 1;
            while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '.' || text[end] == '_' ||
                                         ((text[end] == '-' || text[end] == '+') && (text[end - 1] == 'e' || text[end - 1] == 'E')))) {
                ++end;
            }
            out += shortest_float(text.substr(i, end - i));
            i = end;
        } else {
            out += c;
            ++i;
        }
    }
    return out;
}

}  // namespace

std::string to_toml(const Material& material) {
    std::ostringstream out;
    out << "# skinspec material, written by skinspec " << "(units in the key names; see docs/MATERIALS.md)\n";
    std::visit(
        [&](const auto& m) {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, LayerStack>) out << stack_table(m, false);
            else out << homogeneous_table(m);
        },
        material);
    out << '\n';
    return with_shortest_floats(out.str());
}

void write_material(const Material& material, const std::filesystem::path& file, bool overwrite) {
    write_text_file(file, to_toml(material), overwrite);
}

namespace {

// The number an override's text reads as (as the file reader would read it), or nullopt for any other value.
std::optional<double> override_number(const MaterialOverride& o) {
    if (o.number) return o.number;  // a sweep's value, whose text is its exact shortest form
    const auto table = override_value(o.value);
    const auto* node = table.get("v");
    if (!node || !node->is_number()) return std::nullopt;
    return node->value<double>();
}

template <class Owner>
const NumberField<Owner>* number_field(const std::vector<NumberField<Owner>>& fields, std::string_view key) {
    for (const auto& f : fields) {
        if (f.key == key) return &f;
    }
    return nullptr;
}

// Sets a number field of `stack` in place, typed, with the reader's range check. False where the override needs
// the file reader (anything but a valid number of a field the stack already holds, a value out of range, a
// contradiction): the caller then takes the TOML path, which gives the reader's own message. One table (the
// field descriptors) serves both paths.
bool set_number_in_place(LayerStack& stack, std::string_view key, std::optional<double> value) {
    const auto dot = key.find('.');
    if (dot == std::string::npos) return false;
    const auto head = key.substr(0, dot);
    const auto name = key.substr(dot + 1);
    if (!value) return false;
    if (head == "model") {
        for (const auto& f : model_fields()) {
            const auto* member = std::get_if<double ModelOptions::*>(&f.member);
            if (f.key != name || !member || !f.range.contains(*value)) continue;
            stack.model.*(*member) = *value;
            return true;
        }
        return false;
    }
    if (head == "surface" || head == "bottom") {
        const auto* f = number_field(head == "surface" ? surface_fields() : bottom_fields(), name);
        if (!f || !f->range.contains(*value)) return false;
        stack.*(f->member) = *value;
        return true;
    }
    // The layers the head names (checked, then set: a refusal leaves the stack as it was).
    const auto matching = [&](TissueLayer& l) { return layer_matches(l.name, head); };
    const auto all_matching = [&](const auto& condition) {
        return std::all_of(stack.layers.begin(), stack.layers.end(), [&](TissueLayer& l) { return !matching(l) || condition(l); });
    };
    const auto set_matching = [&](const auto& set) {
        for (auto& l : stack.layers) {
            if (matching(l)) set(l);
        }
        return true;
    };
    if (std::none_of(stack.layers.begin(), stack.layers.end(), matching)) return false;
    if (const auto* f = number_field(layer_number_fields(), name)) {
        const bool fits = all_matching([&](const TissueLayer& l) {
            const double v_m = f->member == &TissueLayer::melanosome_fraction ? *value : l.melanosome_fraction;
            const double v_b = f->member == &TissueLayer::blood_fraction ? *value : l.blood_fraction;
            return v_m + v_b <= 1.0;
        });
        if (!fits || !f->range.contains(*value)) return false;
        return set_matching([&](TissueLayer& l) { l.*(f->member) = *value; });
    }
    if (const auto* f = number_field(volumetric_fields(), name)) {
        const bool plain = all_matching([&](const TissueLayer& l) {
            return l.volumetric && l.volumetric->source == VolumetricSource::power_law && !(name == "volumetric_g" && is_measured(l.volumetric->phase));
        });
        if (!plain || !f->range.contains(*value)) return false;
        return set_matching([&](TissueLayer& l) { (*l.volumetric).*(f->member) = *value; });
    }
    if (const auto* f = number_field(reduced_power_law_fields(), name)) {
        const bool law = all_matching([](const TissueLayer& l) { return l.reduced && l.reduced->table.empty(); });
        if (!law || !f->range.contains(*value)) return false;
        return set_matching([&](TissueLayer& l) { (*l.reduced).*(f->member) = *value; });
    }
    return false;
}

}  // namespace

void assign_with_overrides(Material& into, const Material& material, const std::vector<MaterialOverride>& overrides) {
    into = material;
    if (overrides.empty()) return;  // to_toml round-trips exactly: nothing to re-check
    if (auto* stack = std::get_if<LayerStack>(&into)) {
        // Numbers (every sweep, most --set) are set in the material directly; anything else goes through the file
        // reader, which also words every refusal.
        if (std::all_of(overrides.begin(), overrides.end(), [&](const MaterialOverride& o) { return set_number_in_place(*stack, o.key, override_number(o)); })) return;
    }
    into = parse_material(to_toml(material), "material " + material_name(material), overrides);
}

void assign_with_values(Material& into, const Material& material, const SweptValues& values) {
    into = material;
    if (auto* stack = std::get_if<LayerStack>(&into)) {
        bool all = true;
        for (std::size_t i = 0; i < values.size() && all; ++i) all = set_number_in_place(*stack, values.field(i), values.values[i]);
        if (all) return;
    }
    assign_with_overrides(into, material, sweep_overrides(values));
}

Material with_overrides(const Material& material, const std::vector<MaterialOverride>& overrides) {
    Material out;
    assign_with_overrides(out, material, overrides);
    return out;
}

namespace {

// The document material_field reads: every model switch spelled out.
toml::table full_table(const Material& material) {
    return std::visit(
        [](const auto& m) {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, LayerStack>) return stack_table(m, true);
            else return homogeneous_table(m);
        },
        material);
}

FieldValue field_value(const toml::node& node, const std::string& key) {
    if (const auto b = node.value_exact<bool>()) return *b;
    if (node.is_number()) return *node.value<double>();
    if (const auto text = node.value_exact<std::string>()) return *text;
    if (const auto* array = node.as_array()) {
        if (array->is_homogeneous(toml::node_type::string)) {
            std::vector<std::string> out;
            for (const auto& e : *array) out.push_back(*e.value_exact<std::string>());
            return out;
        }
        std::vector<double> out;
        for (const auto& e : *array) out.push_back(e.value<double>().value_or(0.0));
        return out;
    }
    throw InputError(key + ": not a value (a table)");
}

std::string keys_text(const toml::table& table, const std::string& prefix) {
    std::string out;
    for (const auto& [k, node] : table) {
        if (k.str() != "name" || prefix.empty()) out += (out.empty() ? "" : ", ") + prefix + std::string(k.str());
    }
    return out;
}

}  // namespace

FieldValue material_field(const Material& material, std::string_view key_text) {
    const std::string key(key_text);
    const auto root = full_table(material);
    const auto dot = key.find('.');
    if (dot == std::string::npos) {
        const auto* node = root.get(key);
        if (!node || node->is_table() || key == "layers") {
            throw InputError("field '" + key + "' is not one of " + material_name(material) + "'s (fields: " + [&] {
                std::string keys;
                for (const auto& k : material_keys(material)) keys += (keys.empty() ? "" : ", ") + k;
                return keys;
            }() + ")");
        }
        return field_value(*node, key);
    }
    const std::string head = key.substr(0, dot);
    const std::string name = key.substr(dot + 1);
    if (head == "model" || head == "surface" || head == "bottom") {
        const auto* section = root.get(head) ? root.get(head)->as_table() : nullptr;
        const auto* node = section ? section->get(name) : nullptr;
        if (!node) throw InputError("field '" + key + "' is not set in " + material_name(material) + " (" + head + " holds: " +
                                    (section ? keys_text(*section, head + ".") : std::string("nothing")) + ")");
        return field_value(*node, key);
    }
    std::vector<std::string> names;
    std::vector<std::pair<std::string, FieldValue>> found;
    std::string missing;
    if (const auto* layers = root.get("layers"); layers && layers->as_array()) {
        for (const auto& node : *layers->as_array()) {
            const auto& layer = *node.as_table();
            const auto layer_name = layer["name"].value_or(std::string());
            names.push_back(layer_name);
            if (!layer_matches(layer_name, head)) continue;
            if (const auto* value = layer.get(name)) found.emplace_back(layer_name, field_value(*value, key));
            else missing = layer_name + " holds: " + keys_text(layer, layer_name + ".");
        }
    }
    if (found.empty() && missing.empty()) throw unknown_section("field '" + key + "'", head, names);
    if (!missing.empty()) throw InputError("field '" + key + "' is not set in " + material_name(material) + " (" + missing + ")");
    for (const auto& [layer_name, value] : found) {
        if (value != found.front().second) {
            throw InputError("field '" + key + "' addresses " + found.front().first + " and " + layer_name +
                             ", which differ: read " + found.front().first + "." + name + " and " + layer_name + "." + name + " one at a time");
        }
    }
    return found.front().second;
}

std::vector<std::string> material_keys(const Material& material) {
    const auto root = full_table(material);
    std::vector<std::string> keys;
    for (const auto& [k, node] : root) {
        const std::string key(k.str());
        if (key == "kind") continue;
        if (const auto* section = node.as_table()) {
            for (const auto& [name, value] : *section) keys.push_back(key + "." + std::string(name.str()));
        } else if (key == "layers") {
            for (const auto& layer_node : *node.as_array()) {
                const auto& layer = *layer_node.as_table();
                const auto layer_name = layer["name"].value_or(std::string());
                for (const auto& [name, value] : layer) {
                    if (name.str() != "name") keys.push_back(layer_name + "." + std::string(name.str()));
                }
            }
        } else {
            keys.push_back(key);
        }
    }
    return keys;
}

}  // namespace skinspec
