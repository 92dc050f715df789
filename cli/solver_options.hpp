#pragma once
// The command-line face of the solver registry, shared by every command that solves: `--mode` and the solver
// switches. A switch left unset keeps the solver's default; a switch the chosen solver does not take is
// refused by the registry (solvers/spectral_solver.hpp), never ignored.
#include <map>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "solvers/spectral_solver.hpp"

namespace skinspec::cli {

struct SolverOptions {
    std::string mode;  // "" = the command's default
    std::map<std::string, std::optional<std::string>> switches;  // by switch name (solvers/solver_switches.hpp); unset: not given
    std::string geometry = "sci";
};

// Adds --mode and one option per switch descriptor, with help texts naming the solvers that declare each. `default_text` describes
// the default of --mode ("biospec"); an empty options.mode means "the command's default".
void add_solver_options(CLI::App& command, SolverOptions& options, const std::string& default_text = "biospec");
// One switch's option alone (a command that offers only some solvers, e.g. fit-spectrum's --channels).
void add_switch_option(CLI::App& command, SolverOptions& options, SolverSwitch id);

// The solver named by --mode, or `fallback` when --mode was not given.
const SpectralSolver& chosen_solver(const SolverOptions& options, std::string_view fallback = "biospec");
// --mode, or the default of the commands that need radial profiles (default_profile_solver: the exact transport).
const SpectralSolver& chosen_profile_solver(const SolverOptions& options);
// The --mode help of those commands.
inline constexpr const char* profile_solver_default = "rte: the exact transport (volumetric walk), with standard errors";
SolverSwitches solver_switches(const SolverOptions& options);
// --geometry (for the commands whose R is a measurement: spectrum, swatch, fit-spectrum).
void add_geometry_option(CLI::App& command, SolverOptions& options);
// The parsed --geometry; notes once what 0-45 costs in rays when `solver` (the one the command uses) traces rays for it.
MeasurementGeometry measurement_geometry(const SolverOptions& options, const SpectralSolver& solver);
// The Monte Carlo settings of the commands that ask for radial profiles (a walk's R(r)): the precision target --stderr
// and its budget --max-rays, or an exact --rays count (rays 0: unset), and --seed; `given` names those the user gave
// (a deterministic solver refuses them).
struct ProfileSampling {
    std::uint64_t rays = 0;
    std::uint64_t seed = 1;
    double stderr_target = default_profile_stderr;
    std::uint64_t max_rays = default_profile_max_rays;
    std::vector<std::string> given;
};
void add_profile_sampling_options(CLI::App& command, ProfileSampling& sampling);
// Fills sampling.given from the parsed command (its callback's first step).
void note_given_profile_sampling(const CLI::App& command, ProfileSampling& sampling);
// solve_profiles with a progress bar labelled `label` on a terminal, stopped by SIGINT, SIGTERM or SIGHUP (the
// channels finished so far come back, partial; InterruptGuard says why).
SpectralProfiles solve_profiles_stoppable(const SpectralSolver& solver, const Material& material, ProfileRequest request, const std::string& label);
// Several materials' profiles together (solve_profiles: a replaying solver shares its paths among them), stoppable.
std::vector<SpectralProfiles> solve_profiles_stoppable(const SpectralSolver& solver, const std::vector<const Material*>& materials, ProfileRequest request,
                                                       const std::string& label);
ProfileRequest profile_request(const WavelengthGrid& wavelengths, const std::vector<double>& radii_mm, bool transmittance, const SolverOptions& options,
                               const ProfileSampling& sampling, std::vector<MaterialOverride> overrides);

}  // namespace skinspec::cli
