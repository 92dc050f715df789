#pragma once
// Material presets: hand-editable TOML files in data/materials (docs/MATERIALS.md). Two kinds:
//   kind = "layered":     a LayerStack (BioSpec skin and any other stack);
//   kind = "homogeneous": a semi-infinite material given by RGB-band (or other band) optical parameters.
// Every field is range-checked; unknown keys are errors; messages name file, line, key, value and range.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "materials/layer_stack.hpp"
#include "materials/swept_values.hpp"

namespace skinspec {

struct HomogeneousMaterial {
    std::string name;
    std::string description;
    double relative_refractive_index = 1.0;
    std::vector<std::string> bands;
    std::vector<double> reduced_scattering_per_mm;
    std::vector<double> absorption_per_mm;
    std::vector<double> published_diffuse_reflectance;  // optional, as printed by the source
    bool operator==(const HomogeneousMaterial&) const = default;
};

using Material = std::variant<LayerStack, HomogeneousMaterial>;

// One "--set KEY=VALUE": KEY is name | description | model.K | surface.K | bottom.K | LAYER.K, where LAYER is a
// layer name or the suffix shared by several ("dermis" sets papillary_dermis and reticular_dermis). VALUE is a
// TOML value (number, true/false, [array]); anything else is taken as a string.
struct MaterialOverride {
    MaterialOverride() = default;
    MaterialOverride(std::string key_text, std::string value_text, std::string origin_option = "--set", std::optional<double> as_number = std::nullopt)
        : key(std::move(key_text)), value(std::move(value_text)), origin(std::move(origin_option)), number(as_number) {}
    std::string key;
    std::string value;
    std::string origin = "--set";  // the option it came from, named in messages ("--set", "--vary")
    std::optional<double> number;  // the value as a number when the maker had one (sweeps): `value` is its exact text
};
MaterialOverride parse_override(std::string_view text);

// The reflector switch of `spectrum --reflector` and Python's reflector=: on (BioSpec's ideal reflector), off (an open
// bottom) or hypodermis (the measured one), as the bottom.boundary override it stands for; InputError naming `origin`
// and the allowed values otherwise.
MaterialOverride reflector_override(std::string_view value, const std::string& origin);
// Its values as a list, "on, off, hypodermis" (help and messages).
std::string reflector_choices();

// Reads a material file and applies the overrides before validation.
Material read_material(const std::filesystem::path& file, const std::vector<MaterialOverride>& overrides = {});
// Material TOML text (a file's contents, or what to_toml wrote); `source` names it in messages.
Material parse_material(std::string_view toml_text, std::string_view source, const std::vector<MaterialOverride>& overrides = {});
// `material` with the overrides applied and checked as when read from a file (messages name "material NAME").
Material with_overrides(const Material& material, const std::vector<MaterialOverride>& overrides);
// The same into `into`, reusing the memory it holds (a sweep builds thousands of members into a few materials).
void assign_with_overrides(Material& into, const Material& material, const std::vector<MaterialOverride>& overrides);
// The same for a sweep member's values (as --vary sets them), set typed where the fields allow (no text).
void assign_with_values(Material& into, const Material& material, const SweptValues& values);
// A preset name (file stem in data/materials) or a path to a .toml file.
Material load_material(std::string_view name_or_file, const std::vector<MaterialOverride>& overrides = {});
std::vector<std::filesystem::path> preset_files();
const std::string& material_name(const Material& material);
const std::string& material_description(const Material& material);
// A changed copy's labels follow its data: `name`, and the description says what changed from what
// ("BioSpec skin, lightly pigmented (...); changed from biospec-lightly: epidermis.melanosome_fraction=0.03").
Material relabelled(Material material, std::string name, const std::vector<MaterialOverride>& changes);

// The value of a field as --set addresses it: NAME, model.NAME (every switch, also those the variant sets),
// surface.NAME, bottom.NAME or LAYER.NAME, where a LAYER suffix ("dermis") must address layers that agree.
// InputError naming the key and what the material holds.
using FieldValue = std::variant<bool, double, std::string, std::vector<double>, std::vector<std::string>>;
FieldValue material_field(const Material& material, std::string_view key);
// Every key material_field reads, in file order (each layer's fields as LAYER.NAME).
std::vector<std::string> material_keys(const Material& material);

// TOML text that read_material turns back into an equal Material.
std::string to_toml(const Material& material);
// Writes to_toml(material) to `file`; an existing file is only replaced when `overwrite` is set.
void write_material(const Material& material, const std::filesystem::path& file, bool overwrite);

}  // namespace skinspec
