#include "cli/solver_options.hpp"

#include <algorithm>
#include <iostream>

#include "cli/common_options.hpp"
#include "cli/progress.hpp"
#include "solvers/matched_multipole_solver.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::cli {

void add_solver_options(CLI::App& command, SolverOptions& o, const std::string& default_text) {
    std::string modes;
    for (const auto* s : solver_registry()) modes += "\n  " + std::string(s->name()) + ": " + std::string(s->description());
    command.add_option("--mode", o.mode, "Solver (default " + default_text + "):" + modes);
    for (const auto& d : switch_descriptors()) {
        if (d.parse) add_switch_option(command, o, d.id);
    }
}

void add_switch_option(CLI::App& command, SolverOptions& o, SolverSwitch id) {
    const auto& d = describe(id);
    std::string takers;
    for (const auto* s : solver_registry()) {
        const auto& declared = s->capabilities().switches;
        if (std::find(declared.begin(), declared.end(), d.id) != declared.end()) takers += (takers.empty() ? "" : ", ") + std::string(s->name());
    }
    command.add_option_function<std::string>(
        "--" + std::string(d.name), [&o, name = std::string(d.name)](const std::string& value) { o.switches[name] = value; },
        takers + ": " + std::string(d.values));
}

const SpectralSolver& chosen_solver(const SolverOptions& o, std::string_view fallback) {
    return find_solver(o.mode.empty() ? fallback : std::string_view(o.mode), "--mode");
}

const SpectralSolver& chosen_profile_solver(const SolverOptions& o) {
    return o.mode.empty() ? default_profile_solver() : chosen_solver(o);
}

SolverSwitches solver_switches(const SolverOptions& o) {
    SolverSwitches s;
    for (const auto& d : switch_descriptors()) {
        const auto given = o.switches.find(std::string(d.name));
        if (d.parse && given != o.switches.end() && given->second) d.parse(s, *given->second, "--" + std::string(d.name));
    }
    return s;
}

void add_geometry_option(CLI::App& command, SolverOptions& o) {
    command.add_option("--geometry", o.geometry,
                       "How R is measured: sci (specular included, all light leaving the top), sce (specular excluded: without "
                       "the first-surface reflection), 0-45 (normal incidence, reflectance factor at 40-50 deg exit; biospec; only the "
                       "rays leaving in that ring count, so a standard error takes about 8x the rays of sci)")
        ->capture_default_str();
}

MeasurementGeometry measurement_geometry(const SolverOptions& o, const SpectralSolver& solver) {
    const auto geometry = parse_measurement_geometry(o.geometry, "--geometry");
    static bool noted = false;  // once per command, however often it asks
    // Only where it applies: a solver that refuses 0-45, or computes it without rays, is told nothing about rays.
    const auto& caps = solver.capabilities();
    const bool measures = std::find(caps.geometries.begin(), caps.geometries.end(), geometry) != caps.geometries.end();
    if (geometry == MeasurementGeometry::zero_45 && measures && caps.uncertainty && !noted) {
        noted = true;
        // Measured: biospec-lightly, --stderr 0.002, 31 wavelengths: sci 0.28 s, 0-45 2.24 s (docs/BIOSPEC.md).
        std::cerr << "skinspec: note: --geometry 0-45 counts only the rays leaving at 40-50 deg: the same standard error takes about 8x "
                     "the rays (and time) of sci\n";
    }
    return geometry;
}

void add_profile_sampling_options(CLI::App& command, ProfileSampling& sampling) {
    auto* target = command.add_option("--stderr", sampling.stderr_target,
                                      "rte: each wavelength runs until the standard error of the reflectance leaving within every radius of a "
                                      "1-2-5 series up to the reach is at most this")
                       ->capture_default_str()
                       ->check(CLI::Range(1e-6, 0.5));
    auto* budget = add_ray_count_option(command, "--max-rays", sampling.max_rays, "rte: photon budget per wavelength with --stderr")->capture_default_str();
    add_ray_count_option(command, "--rays", sampling.rays, "rte: exactly this many photons per wavelength instead of --stderr")->excludes(target)->excludes(budget);
    add_seed_option(command, sampling.seed, "rte: random seed");
}

void note_given_profile_sampling(const CLI::App& command, ProfileSampling& sampling) {
    sampling.given = given_options(command, {"--seed", "--max-rays", "--stderr"});
}

std::vector<SpectralProfiles> solve_profiles_stoppable(const SpectralSolver& solver, const std::vector<const Material*>& materials, ProfileRequest request,
                                                       const std::string& label) {
    const InterruptGuard interrupt;
    ProgressBar bar(label);
    request.cancel = &InterruptGuard::cancel_flag();
    request.on_progress = [&bar](const Progress& p) { bar(p); };
    auto profiles = solve_profiles(solver, materials, request);
    bar.clear();
    return profiles;
}

SpectralProfiles solve_profiles_stoppable(const SpectralSolver& solver, const Material& material, ProfileRequest request, const std::string& label) {
    return solve_profiles_stoppable(solver, std::vector<const Material*>{&material}, std::move(request), label).front();
}

ProfileRequest profile_request(const WavelengthGrid& wavelengths, const std::vector<double>& radii_mm, bool transmittance, const SolverOptions& options,
                               const ProfileSampling& sampling, std::vector<MaterialOverride> overrides) {
    ProfileRequest request;
    request.wavelengths = wavelengths;
    request.radii_mm = radii_mm;
    request.transmittance = transmittance;
    request.switches = solver_switches(options);
    if (sampling.rays > 0) request.rays_per_wavelength = sampling.rays;
    request.stderr_target = sampling.stderr_target;
    request.max_rays_per_wavelength = sampling.max_rays;
    request.seed = sampling.seed;
    request.sampling_options = sampling.given;
    request.overrides = std::move(overrides);
    return request;
}

}  // namespace skinspec::cli
