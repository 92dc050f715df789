#include "cli/solver_options.hpp"

#include "spectral/input_error.hpp"

namespace skinspec::cli {

void add_solver_options(CLI::App& command, SolverOptions& o, const std::string& default_text) {
    std::string modes;
    for (const auto* s : solver_registry()) modes += "\n  " + std::string(s->name()) + ": " + std::string(s->description());
    command.add_option("--mode", o.mode, "Solver (default " + default_text + "):" + modes);
    command.add_option("--estimator", o.estimator, "biospec: absorption estimator, weighted (default) or random (per-crossing test)");
    command.add_option("--fold-into-skin", o.fold_into_skin,
                       "biospec: fold-perturbed reflections pointing into the skin, drop (default, as the 2004 code) or resample");
    command.add_option("--boundaries", o.boundaries, "rte: Fresnel at the outer boundaries, random (default, as MCML) or split");
    command.add_option("--roughness", o.roughness, "dipole, multipole: Beckmann RMS slope of a rough top surface, (0, 2] (default smooth)")
        ->check(CLI::Range(1e-6, 2.0));
    command.add_option("--channels", o.channels,
                       "adding-doubling: quadrature channels per hemisphere, [4, 256] (default 24; the stated accuracy falls about as 1/channels, "
                       "the time grows as channels^3)");
}

const SpectralSolver& chosen_solver(const SolverOptions& o, std::string_view fallback) {
    return find_solver(o.mode.empty() ? fallback : std::string_view(o.mode), "--mode");
}

SolverSwitches solver_switches(const SolverOptions& o) {
    SolverSwitches s;
    if (!o.estimator.empty()) s.estimator = parse_absorption_estimator(o.estimator, "--estimator");
    if (!o.fold_into_skin.empty()) s.fold_into_skin = parse_fold_into_skin(o.fold_into_skin, "--fold-into-skin");
    if (!o.boundaries.empty()) s.boundaries = parse_boundary_mode(o.boundaries, "--boundaries");
    if (o.roughness > 0.0) s.surface_roughness = o.roughness;
    if (o.channels > 0) s.quadrature_channels = o.channels;
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
    command.add_option("--seed", seed, "rte: random seed")->capture_default_str()->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 63));
}

ProfileRequest profile_request(const WavelengthGrid& wavelengths, const std::vector<double>& radii_mm, bool transmittance, const SolverOptions& options,
                               std::uint64_t rays, std::uint64_t seed) {
    return ProfileRequest{wavelengths, radii_mm, transmittance, solver_switches(options), rays > 0 ? std::optional(rays) : std::nullopt, seed};
}

}  // namespace skinspec::cli
