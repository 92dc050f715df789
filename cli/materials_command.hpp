#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec materials list | show | save`: the material presets and per-layer optics.
void add_materials_command(CLI::App& app);

}  // namespace skinspec::cli
