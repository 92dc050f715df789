#pragma once
// Options many commands share, declared once with their checks: --seed (a whole number in [0, 2^63]), the ray
// counts and --overwrite (alias --force). Material options: cli/material_options.hpp; solver options: cli/solver_options.hpp.
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace skinspec::cli {

CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& help = "Random seed");
// A Monte Carlo ray count or budget per wavelength (--rays, --max-rays): a whole number in
// [minimum_rays_per_wavelength, maximum_rays_per_wavelength] (transport/spectral_request.hpp says why the minimum).
CLI::Option* add_ray_count_option(CLI::App& command, const std::string& name, std::uint64_t& rays, const std::string& help);
CLI::Option* add_overwrite_flag(CLI::App& command, bool& overwrite, const std::string& help = "Replace existing output files");
// Checks added to every option of `app` and its subcommands by type, one place for every command present and future:
// a number (FLOAT) refuses nan and inf, which CLI11's own range checks let through ("--stderr nan" was accepted); a
// whole number (INT, UINT) takes "1e3" when it is whole, and an unsigned one refuses a minus sign ("--gaussians -1"
// became 18446744073709551615); a text (TEXT) refuses an empty value.
void check_option_values(CLI::App& app);
// The options of `names` the user gave to `command` (for refusals that name them), e.g. {"--seed"}.
std::vector<std::string> given_options(const CLI::App& command, const std::vector<std::string>& names);
// The Monte Carlo options of a command that a deterministic solver refuses when given (SolverRequest::sampling_options).
std::vector<std::string> given_sampling_options(const CLI::App& command);

}  // namespace skinspec::cli
