#pragma once
// What every command that takes a base material shares: the --set help text (so they all say where the keys
// are), the choice between --preset and --material, and the parsed --set overrides.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::cli {

inline constexpr const char* set_option_help =
    "Override a material field, KEY=VALUE (repeatable), e.g. epidermis.melanosome_fraction=0.1. KEY is a field of the "
    "material file: LAYER.FIELD (LAYER a layer name, or a suffix such as 'dermis' for all dermal layers), model.FIELD, "
    "surface.FIELD, bottom.FIELD; 'skinspec materials keys' lists every field with its unit and range";

// The --material file or the --preset given (InputError for both), biospec-moderately when neither is.
inline std::string chosen_material(const std::string& preset, const std::string& material_file) {
    if (!preset.empty() && !material_file.empty()) throw InputError("give --preset or --material, not both");
    return !material_file.empty() ? material_file : preset.empty() ? "biospec-moderately" : preset;
}

// --preset, --material and --set of a command that takes one base material, declared once (chosen_material picks
// between the first two).
inline void add_base_material_options(CLI::App& command, std::string& preset, std::string& material_file, std::vector<std::string>& overrides,
                                      const std::string& default_preset = "biospec-moderately") {
    command.add_option("--preset", preset, "Preset name (default " + default_preset + "; see 'skinspec materials list')");
    command.add_option("--material", material_file, "Material TOML file (instead of --preset)");
    command.add_option("--set", overrides, set_option_help);
}

inline std::vector<MaterialOverride> parsed_overrides(const std::vector<std::string>& texts) {
    std::vector<MaterialOverride> out;
    for (const auto& t : texts) out.push_back(parse_override(t));
    return out;
}

}  // namespace skinspec::cli
