#include "cli/export_command.hpp"

namespace skinspec::cli {

void add_export_command(CLI::App& app) {
    auto* exporter = app.add_subcommand("export", "Skin for renderers and peers: look-up textures, Gaussian-sum profiles, pbrt-v4 and Mitsuba 3 media, MCML input");
    exporter->require_subcommand(1);
    add_export_lut_command(*exporter);
    add_export_profile_command(*exporter);
    add_export_scene_commands(*exporter);
    add_export_mcml_command(*exporter);
}

}  // namespace skinspec::cli
