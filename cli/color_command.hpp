#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec color [FILE]`: colour of a reflectance/transmittance spectrum.
void add_color_command(CLI::App& app);

}  // namespace skinspec::cli
