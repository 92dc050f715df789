#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec fit-image IMAGE`: per-pixel melanosome and blood maps of a skin albedo image (RGB or multispectral)
// through the skin model, with uncertainties, residuals, a mask of what is not skin, and edits re-rendered
// (inverse/image_fit, docs/FIT_IMAGE.md).
void add_fit_image_command(CLI::App& app);

}  // namespace skinspec::cli
