#pragma once
#include <CLI/CLI.hpp>

namespace skinspec::cli {

// `skinspec phase-study`: the experiments of Baranoski et al. 2005 (HG fits, sampling errors, goniometer, cost, phantoms).
void add_phase_study_command(CLI::App& app);

}  // namespace skinspec::cli
