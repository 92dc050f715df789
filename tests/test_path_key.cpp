// Path keys: which stacks share traced paths, derived from the field table's absorption_only declarations.
#include <catch2/catch.hpp>

#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"
#include "materials/path_key.hpp"
#include "spectral/text_fields.hpp"

using namespace skinspec;

TEST_CASE("stacks that differ only in absorption-only fields have equal path keys", "[path_key]") {
    // The preset's own volumetric description: a derived one separates them for the volumetric walk (test_matched_volumetric).
    const auto a = std::get<LayerStack>(load_material("biospec-moderately", {parse_override("model.volumetric_matched_to_biospec=false")}));
    for (const auto& field : absorption_only_fields()) {
        const auto key = field.starts_with("LAYER.") ? "epidermis." + field.substr(6) : field;
        const auto& value = material_field(a, key);
        const std::string changed = std::holds_alternative<bool>(value) ? (std::get<bool>(value) ? "false" : "true")
                                                                         : format_number(std::get<double>(value) == 0.0 ? 0.01 : std::get<double>(value) * 0.9);
        const auto b = std::get<LayerStack>(with_overrides(a, {{key, changed}}));
        INFO(key);
        CHECK(is_absorption_only_key(key));
        CHECK_FALSE(a == b);
        CHECK(path_key(a, TracedPaths::volumetric) == path_key(b, TracedPaths::volumetric));
        CHECK(path_difference(a, b, TracedPaths::volumetric).empty());
    }
}

TEST_CASE("every other field separates the keys and is named by its --set key", "[path_key]") {
    const auto a = std::get<LayerStack>(load_material("biospec-moderately"));
    auto b = a;
    b.layers[1].thickness_cm *= 2.0;
    CHECK_FALSE(path_key(a, TracedPaths::volumetric) == path_key(b, TracedPaths::volumetric));
    CHECK(path_difference(a, b, TracedPaths::volumetric) == "epidermis.thickness_cm");
    b = a;
    b.name = "renamed";
    b.description = "other words";
    CHECK(path_difference(a, b, TracedPaths::volumetric).empty());
    b = a;
    b.model.dermal_rayleigh = false;
    CHECK(path_difference(a, b, TracedPaths::volumetric) == "model.dermal_rayleigh");
    b = a;
    b.layers.pop_back();
    CHECK(path_difference(a, b, TracedPaths::volumetric) == "the number of layers");
    b = a;
    b.layers[2].volumetric->g = 0.5;
    CHECK(path_difference(a, b, TracedPaths::volumetric) == "papillary_dermis.volumetric_g");
    CHECK_FALSE(is_absorption_only_key("epidermis.thickness_cm"));
    CHECK_FALSE(is_absorption_only_key("surface.fold_aspect_ratio"));
}
