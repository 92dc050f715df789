#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec iad [FILE.rxt]`: optical properties of a slab from integrating-sphere measurements by inverse
// adding-doubling (inverse/iad, docs/IAD.md).
void add_iad_command(CLI::App& app);

}  // namespace skinspec::cli
