#include "cli/solver_options.hpp"

#include <algorithm>

#include "cli/common_options.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::cli {

void add_solver_options(CLI::App& command, SolverOptions& o, const std::string& default_text) {
    std::string modes;
    for (const auto* s : solver_registry()) modes += "\n  " + std::string(s->name()) + ": " + std::string(s->description());
    command.add_option("--mode", o.mode, "Solver (default " + default_text + "):" + modes);
    for (const auto& d : switch_descriptors()) {
        if (!d.parse) continue;
        std::string takers;
        for (const auto* s : solver_registry()) {
            const auto& declared = s->capabilities().switches;
            if (std::find(declared.begin(), declared.end(), d.id) != declared.end()) takers += (takers.empty() ? "" : ", ") + std::string(s->name());
        }
        command.add_option_function<std::string>(
            "--" + std::string(d.name), [&o, name = std::string(d.name)](const std::string& value) { o.switches[name] = value; },
            takers + ": " + std::string(d.values));
    }
}

const SpectralSolver& chosen_solver(const SolverOptions& o, std::string_view fallback) {
    return find_solver(o.mode.empty() ? fallback : std::string_view(o.mode), "--mode");
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
                       "the first-surface reflection), 0-45 (normal incidence, reflectance factor at 40-50 deg exit; biospec)")
        ->capture_default_str();
}

MeasurementGeometry measurement_geometry(const SolverOptions& o) { return parse_measurement_geometry(o.geometry, "--geometry"); }

void add_profile_ray_options(CLI::App& command, std::uint64_t& rays, std::uint64_t& seed) {
    command.add_option("--rays", rays, "rte: photons per wavelength for R(r) (default 1000000); refused by deterministic solvers")
        ->check(CLI::PositiveNumber);
    add_seed_option(command, seed, "rte: random seed");
}

ProfileRequest profile_request(const WavelengthGrid& wavelengths, const std::vector<double>& radii_mm, bool transmittance, const SolverOptions& options,
                               std::uint64_t rays, std::uint64_t seed, std::vector<std::string> sampling_options) {
    return ProfileRequest{wavelengths, radii_mm, transmittance, solver_switches(options), rays > 0 ? std::optional(rays) : std::nullopt, seed, nullptr, std::move(sampling_options)};
}

}  // namespace skinspec::cli
