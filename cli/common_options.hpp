#pragma once
// Options many commands share, declared once with their checks: --seed (a whole number in [0, 2^63]) and
// --overwrite (alias --force). Material options: cli/material_options.hpp; solver options: cli/solver_options.hpp.
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace skinspec::cli {

CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& help = "Random seed");
CLI::Option* add_overwrite_flag(CLI::App& command, bool& overwrite, const std::string& help = "Replace existing output files");
// Every number option of `app` and its subcommands (CLI11 type FLOAT) refuses nan and inf, which CLI11's own range
// checks let through ("--stderr nan" was accepted), and every text option an empty value: one check for every
// command, present and future.
void require_finite_numbers(CLI::App& app);

}  // namespace skinspec::cli
