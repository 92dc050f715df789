#include "cli/spectrum_command.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "cli/process_group.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"
#include "materials/parameter_sweep.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/parallel_indices.hpp"

namespace skinspec::cli {
namespace {

struct SpectrumOptions {
    std::vector<std::string> presets;
    std::vector<std::string> materials;
    std::vector<std::string> overrides;
    std::vector<std::string> vary;
    std::vector<std::string> layers;
    std::string wavelengths = "400:700:10";
    double incidence_deg = 0.0;
    std::uint64_t rays = 0;
    double stderr_target = 0.0;
    std::uint64_t max_rays = 10'000'000;
    std::uint64_t seed = 1;
    std::vector<std::string> sampling_given;
    std::vector<std::string> names_in_order;  // --preset and --material values in command-line order  // --seed, --max-rays as given (refused by deterministic solvers)
    unsigned threads = 0;
    std::string quantities = "R";
    std::string reflector;
    std::string variant;
    SolverOptions solver;
    std::string output;
    std::string plot;
    bool force = false;
    bool json = false;
    std::string illuminant = "D65";
    std::string observer = "2";
};

std::vector<MaterialOverride> overrides_for(const SpectrumOptions& o) {
    std::vector<MaterialOverride> out;
    if (!o.variant.empty()) out.push_back({"model.variant", o.variant, "--variant"});
    for (const auto& t : o.overrides) out.push_back(parse_override(t));
    if (!o.reflector.empty()) out.push_back(reflector_override(o.reflector, "--reflector"));
    return out;
}

void run_spectrum(const SpectrumOptions& o) {
    auto names = o.names_in_order;
    if (names.empty()) names = {"biospec-lightly", "biospec-moderately", "biospec-heavily"};
    const auto& solver = chosen_solver(o.solver);

    SolverRequest request;
    request.overrides = overrides_for(o);
    request.sampling_options = o.sampling_given;
    request.switches = solver_switches(o.solver);
    auto& spectral = request.spectral;
    spectral.wavelengths = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    spectral.quantities = parse_quantities(o.quantities, "--quantities");
    spectral.incidence_deg = o.incidence_deg;
    spectral.geometry = measurement_geometry(o.solver, solver);
    spectral.seed = o.seed;
    spectral.max_rays_per_wavelength = o.max_rays;
    if (o.rays > 0) request.fixed_rays_per_wavelength = o.rays;
    else if (o.stderr_target > 0.0) spectral.stderr_target = o.stderr_target;
    else if (solver.capabilities().uncertainty) spectral.stderr_target = 0.002;
    const auto illuminant = parse_illuminant(o.illuminant, "--illuminant");
    const auto observer = parse_observer(o.observer, "--observer");
    if (!o.output.empty()) check_output_path(o.output, o.force, {".csv", ".json"});
    if (!o.plot.empty()) check_output_path(o.plot, o.force, {".png", ".svg"});

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    spectral.cancel = &InterruptGuard::cancel_flag();

    std::vector<ParameterSweep> sweeps;
    for (const auto& v : o.vary) sweeps.push_back(parse_sweep(v));
    if (sweeps.size() > 2) throw InputError("--vary: at most two fields (they form a grid); got " + std::to_string(sweeps.size()));
    const auto axes = sweep_axes(sweeps);

    // Every material (and every combination of the sweeps) is loaded and checked against the solver before
    // any ray is traced.
    std::vector<SweepMembers> members_per_name;
    for (const auto& name : names) {
        auto members = sweep_members(solver, request, axes, o.layers, load_material(name, request.overrides));
        const bool bands = std::holds_alternative<HomogeneousMaterial>(*members.base(0));
        if (!members_per_name.empty() && bands != std::holds_alternative<HomogeneousMaterial>(*members_per_name.front().base(0))) {
            throw InputError("material '" + name + "' has " + (bands ? "bands" : "wavelengths") + ", the materials before it " +
                             (bands ? "wavelengths" : "bands") + ": run them separately");
        }
        if (!o.plot.empty() && bands) throw InputError("--plot: " + name + " has bands, not wavelengths, to plot against");
        members_per_name.push_back(std::move(members));
    }

    ReportedSpectra spectra;
    std::size_t results_expected = 0;
    for (const auto& members : members_per_name) results_expected += members.size();
    spectra.results.reserve(results_expected);
    for (std::size_t m = 0; m < names.size(); ++m) {
        if (InterruptGuard::interrupted() && !process_work_share()) break;  // every rank takes part in every gather
        ProgressBar bar(material_name(*members_per_name[m].base(0)));
        if (is_root_process()) spectral.on_progress = [&bar](const Progress& p) { bar(p); };
        const auto start = std::chrono::steady_clock::now();
        solve_sweep(solver, members_per_name[m], request, spectra.results, process_work_share());
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        bar.clear();
        spectra.seconds.resize(spectra.results.size(), seconds / static_cast<double>(members_per_name[m].size()));
    }

    // With several processes (mpirun), rank 0 has every result and reports; the others are done.
    if (!is_root_process()) return;
    spectra.colors.resize(spectra.results.size());
    parallel_indices(spectra.size(), [&](std::size_t i) {
        const auto& result = spectra.results[i];
        auto color = result.bands.empty() ? reflectance_color(result, illuminant, observer) : std::nullopt;
        if (color) spectra.colors[i] = std::make_shared<const ColorSummary>(std::move(*color));
    });
    // One summary per material, over all of its sweep's members.
    for (std::size_t i = 0, j = 0; i < spectra.size(); i = j) {
        std::vector<const SpectralResult*> results;
        for (j = i; j < spectra.size() && spectra[j].result.material == spectra[i].result.material; ++j) results.push_back(&spectra[j].result);
        const auto& name = spectra[i].result.material;
        print_warning_summary(j - i > 1 ? name + " (" + std::to_string(j - i) + " results)" : name, results);
    }
    if (o.json) std::cout << to_json(spectra).dump(2) << '\n';
    else if (sweeps.empty()) std::cout << to_table(spectra);
    else write_sweep_table(std::cout, spectra);
    if (!o.output.empty()) {
        const bool json_file = o.output.ends_with(".json");
        if (json_file) write_text_file(o.output, to_json(spectra).dump(2) + "\n", true);
        else write_text_file(o.output, [&](std::ostream& out) { write_csv(out, spectra); }, true);
        std::cerr << "wrote " << o.output << '\n';
    }
    // A stop before the first wavelength leaves nothing to plot: no plot, and the stop's exit code (not an input error).
    const bool stopped_empty = InterruptGuard::interrupted() && std::none_of(spectra.results.begin(), spectra.results.end(), [](const SpectralResult& r) {
                                   return !r.wavelengths.empty();
                               });
    if (!o.plot.empty() && !spectra.empty() && !stopped_empty) {
        write_plot(o.plot, spectra);
        std::cerr << "wrote " << o.plot << '\n';
    }
    if (InterruptGuard::interrupted()) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": the wavelengths finished so far were written, marked partial\n";
        std::exit(InterruptGuard::exit_code());
    }
}

}  // namespace

void add_spectrum_command(CLI::App& app) {
    auto o = std::make_shared<SpectrumOptions>();
    auto* cmd = app.add_subcommand("spectrum",
                                   "Skin spectra with the BioSpec walk, the volumetric walk or diffusion (default: lightly, moderately "
                                   "and heavily pigmented presets, 400-700 nm)");
    cmd->add_option("--preset", o->presets, "Preset name (repeatable; see 'skinspec materials list')");
    cmd->add_option("--material", o->materials, "Material TOML file (repeatable)");
    cmd->add_option("--set", o->overrides, set_option_help);
    cmd->add_option("--vary", o->vary,
                    "FIELD=FIRST:LAST:STEPS[:log] (at most two: a grid), one result per combination. Fields that change only "
                    "absorption are replayed from one set of traced paths by the solvers that can (biospec: " +
                        [] {
                            std::string keys;
                            for (const auto& k : absorption_only_fields()) keys += (keys.empty() ? "" : ", ") + k;
                            return keys;
                        }() +
                        "); any other field is traced anew per value");
    cmd->add_option("--layers", o->layers, "Simulate only these layers (comma list), e.g. stratum_corneum,epidermis")->delimiter(',');
    cmd->add_option("--wavelengths", o->wavelengths, "FIRST:LAST:STEP, one wavelength or a comma list (nm)")->capture_default_str();
    cmd->add_option("--incidence", o->incidence_deg, "Polar angle of the incident beam, deg, [0, 90)")->capture_default_str();
    auto* rays = add_ray_count_option(*cmd, "--rays", o->rays, "Fixed number of rays per wavelength");
    auto* se = cmd->add_option("--stderr", o->stderr_target, "Stop each wavelength once the standard error of R (and T) is below this (default 0.002)")
                   ->check(CLI::PositiveNumber);
    rays->excludes(se);
    add_ray_count_option(*cmd, "--max-rays", o->max_rays, "Ray budget per wavelength with --stderr")->capture_default_str();
    add_seed_option(*cmd, o->seed, "Random seed (results are identical for any thread count)");
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--quantities", o->quantities, "Comma list of R, T, A (absorptance per layer), brdf (angular)")->capture_default_str();
    cmd->add_option("--reflector", o->reflector,
                    "Bottom: " + reflector_choices() + " (on: BioSpec's ideal reflector; off: light leaving the bottom is transmittance; "
                    "hypodermis: the measured hypodermis' reflectance, 374-1602 nm, what it keeps is T)");
    cmd->add_option("--variant", o->variant,
                    "Model variant: biospec (default), biospec-2004, biospec-authors-code (reproduces the authors' current code, "
                    "its defects included; not physics)");
    add_solver_options(*cmd, o->solver);
    add_geometry_option(*cmd, o->solver);
    cmd->add_option("--output", o->output, "Write the result to FILE.csv or FILE.json");
    cmd->add_option("--plot", o->plot, "Plot R (and T) with +-2 standard-error bands to FILE.png or FILE.svg");
    add_overwrite_flag(*cmd, o->force, "Replace the --output / --plot files if they exist");
    cmd->add_flag("--json", o->json, "Print the JSON result on standard output");
    cmd->add_option("--illuminant", o->illuminant, "Illuminant for the colour summary: D65, D50, A, E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "Observer for the colour summary: 2 or 10")->capture_default_str();
    cmd->callback([o, cmd] {
        o->sampling_given = given_sampling_options(*cmd);
        // The materials in the order given (columns and results follow it), --preset and --material mixed.
        const auto* preset = cmd->get_option("--preset");
        const auto* material = cmd->get_option("--material");
        std::size_t p = 0, m = 0;
        o->names_in_order.clear();
        for (const auto* option : cmd->parse_order()) {
            if (option == preset && p < o->presets.size()) o->names_in_order.push_back(o->presets[p++]);
            else if (option == material && m < o->materials.size()) o->names_in_order.push_back(o->materials[m++]);
        }
        // Several values after one option ("--preset a b") are one entry of the parse order: the rest, in order.
        o->names_in_order.insert(o->names_in_order.end(), o->presets.begin() + static_cast<std::ptrdiff_t>(p), o->presets.end());
        o->names_in_order.insert(o->names_in_order.end(), o->materials.begin() + static_cast<std::ptrdiff_t>(m), o->materials.end());
        run_spectrum(*o);
    });
}

}  // namespace skinspec::cli
