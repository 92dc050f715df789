#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec export lut|profile|pbrt|mitsuba`: skin for renderers (docs/EXPORT.md). One file per export:
// export_lut_command.cpp, export_profile_command.cpp, export_scene_command.cpp, export_mcml_command.cpp.
void add_export_command(CLI::App& app);

void add_export_lut_command(CLI::App& exporter);
void add_export_profile_command(CLI::App& exporter);
void add_export_scene_commands(CLI::App& exporter);
void add_export_mcml_command(CLI::App& exporter);

}  // namespace skinspec::cli
