#include "cli/spectrum_command.hpp"

#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "cli/progress.hpp"
#include "cli/spectral_output.hpp"
#include "layers/biospec/biospec_solver.hpp"
#include "layers/diffusion/diffusion_model.hpp"
#include "layers/rte/rte_model.hpp"
#include "materials/material_file.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::cli {
namespace {

struct SpectrumOptions {
    std::vector<std::string> presets;
    std::vector<std::string> materials;
    std::vector<std::string> overrides;
    std::vector<std::string> layers;
    std::string wavelengths = "400:700:10";
    double incidence_deg = 0.0;
    std::uint64_t rays = 0;
    double stderr_target = 0.0;
    std::uint64_t max_rays = 10'000'000;
    std::uint64_t seed = 1;
    unsigned threads = 0;
    std::string quantities = "R";
    std::string reflector;
    std::string variant;
    std::string mode = "biospec";
    double roughness = 0.0;
    std::string estimator = "weighted";
    std::string fold_into_skin = "drop";
    std::string output;
    std::string plot;
    bool force = false;
    bool json = false;
    std::string illuminant = "D65";
    std::string observer = "2";
};

Quantities parse_quantities(const std::string& text) {
    Quantities q{false, false, false, false};
    std::string item;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        if (i < text.size() && text[i] != ',') {
            item += text[i];
            continue;
        }
        if (item == "R") q.reflectance = true;
        else if (item == "T") q.transmittance = true;
        else if (item == "A") q.absorptance = true;
        else if (item == "brdf" || item == "angular") q.angular = true;
        else throw InputError("--quantities: '" + item + "' is not a quantity (allowed: R, T, A, brdf)");
        item.clear();
    }
    return q;
}

std::vector<MaterialOverride> overrides_for(const SpectrumOptions& o) {
    std::vector<MaterialOverride> out;
    if (!o.variant.empty()) out.push_back({"model.variant", o.variant});
    for (const auto& t : o.overrides) out.push_back(parse_override(t));
    if (o.reflector == "on") out.push_back({"bottom.boundary", "diffuse_reflector"});
    else if (o.reflector == "off") out.push_back({"bottom.boundary", "exit"});
    else if (!o.reflector.empty()) throw InputError("--reflector: '" + o.reflector + "' is not allowed (allowed: on, off)");
    return out;
}

void run_spectrum(const SpectrumOptions& o) {
    auto names = o.presets;
    names.insert(names.end(), o.materials.begin(), o.materials.end());
    if (names.empty()) names = {"biospec-lightly", "biospec-moderately", "biospec-heavily"};
    const auto overrides = overrides_for(o);

    SpectralRequest request;
    request.wavelengths = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    request.quantities = parse_quantities(o.quantities);
    request.incidence_deg = o.incidence_deg;
    request.seed = o.seed;
    if (o.rays > 0) {
        request.max_rays_per_wavelength = o.rays;
    } else {
        request.stderr_target = o.stderr_target > 0.0 ? o.stderr_target : 0.002;
        request.max_rays_per_wavelength = o.max_rays;
    }
    if (o.mode != "biospec" && o.mode != "rte" && o.mode != "dipole" && o.mode != "multipole") {
        throw InputError("--mode: '" + o.mode + "' is not a mode (allowed: biospec, rte, dipole, multipole)");
    }
    const bool diffusion = o.mode == "dipole" || o.mode == "multipole";
    DiffusionOptions diffusion_options;
    if (diffusion) diffusion_options.mode = parse_diffusion_mode(o.mode, "--mode");
    if (o.roughness > 0.0) {
        if (!diffusion) throw InputError("--roughness: only the diffusion modes (dipole, multipole) model a rough surface");
        diffusion_options.surface_roughness = o.roughness;
    }
    BiospecOptions options;
    options.estimator = parse_absorption_estimator(o.estimator, "--estimator");
    options.fold_into_skin = parse_fold_into_skin(o.fold_into_skin, "--fold-into-skin");
    const auto illuminant = parse_illuminant(o.illuminant, "--illuminant");
    const auto observer = parse_observer(o.observer, "--observer");
    for (const auto& file : {o.output, o.plot}) {
        if (!file.empty() && !o.force && std::filesystem::exists(file)) {
            throw InputError(file + ": exists already (use --overwrite to replace it)");
        }
    }
    if (!o.plot.empty() && !o.plot.ends_with(".png") && !o.plot.ends_with(".svg")) {
        throw InputError("--plot " + o.plot + ": extension not supported (allowed: .png, .svg)");
    }

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    request.cancel = &InterruptGuard::cancel_flag();

    std::vector<ReportedSpectrum> spectra;
    for (const auto& name : names) {
        if (InterruptGuard::interrupted()) break;
        const auto material = load_material(name, overrides);
        const auto* full = std::get_if<LayerStack>(&material);
        if (const auto* homogeneous = std::get_if<HomogeneousMaterial>(&material); homogeneous && diffusion) {
            if (!spectra.empty() && spectra.front().result.bands.empty()) {
                throw InputError("material '" + name + "' has bands, the materials before it wavelengths: run them separately");
            }
            const auto start = std::chrono::steady_clock::now();
            auto result = solve_diffusion_bands(*homogeneous, request, diffusion_options);
            spectra.push_back({std::move(result), std::nullopt, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
            continue;
        }
        if (full && !spectra.empty() && !spectra.front().result.bands.empty()) {
            throw InputError("material '" + name + "' has wavelengths, the materials before it bands: run them separately");
        }
        if (!full) {
            throw InputError("material '" + name + "' is homogeneous; the BioSpec walk needs a layered material "
                             "(homogeneous materials are for the diffusion modes)");
        }
        const auto sub = o.layers.empty() ? std::optional<LayerStack>{} : full->sub_stack(o.layers);
        const LayerStack* stack = sub ? &*sub : full;
        ProgressBar bar(stack->name);
        request.on_progress = [&bar](const Progress& p) { bar(p); };
        const auto start = std::chrono::steady_clock::now();
        auto result = diffusion        ? solve_diffusion_spectrum(*stack, request, diffusion_options)
                      : o.mode == "rte" ? solve_rte_spectrum(*stack, request)
                                        : solve_biospec(*stack, request, options);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto color = reflectance_color(result, illuminant, observer);
        spectra.push_back({std::move(result), std::move(color), seconds});
    }

    for (const auto& s : spectra) {
        for (const auto& w : s.result.warnings) std::cerr << "skinspec: warning: " << s.result.material << ": " << w << '\n';
        if (!o.plot.empty() && !s.result.bands.empty()) {
            throw InputError("--plot: " + s.result.material + " has bands (" + std::to_string(s.result.bands.size()) +
                             "), not wavelengths, to plot against");
        }
    }
    if (o.json) std::cout << to_json(spectra).dump(2) << '\n';
    else std::cout << to_table(spectra);
    if (!o.output.empty()) {
        const bool json_file = o.output.ends_with(".json");
        write_text_file(o.output, json_file ? to_json(spectra).dump(2) + "\n" : to_csv(spectra), true);
        std::cerr << "wrote " << o.output << '\n';
    }
    if (!o.plot.empty() && !spectra.empty()) {
        write_plot(o.plot, spectra);
        std::cerr << "wrote " << o.plot << '\n';
    }
    if (InterruptGuard::interrupted()) {
        std::cerr << "skinspec: interrupted: the wavelengths finished so far were written, marked partial\n";
        std::exit(130);
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
    cmd->add_option("--set", o->overrides, "Override a material field, KEY=VALUE (repeatable), e.g. epidermis.melanosome_fraction=0.1");
    cmd->add_option("--layers", o->layers, "Simulate only these layers (comma list), e.g. stratum_corneum,epidermis")->delimiter(',');
    cmd->add_option("--wavelengths", o->wavelengths, "FIRST:LAST:STEP, one wavelength or a comma list (nm)")->capture_default_str();
    cmd->add_option("--incidence", o->incidence_deg, "Polar angle of the incident beam, deg, [0, 90)")->capture_default_str();
    auto* rays = cmd->add_option("--rays", o->rays, "Fixed number of rays per wavelength")->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 50));
    auto* se = cmd->add_option("--stderr", o->stderr_target, "Stop each wavelength once the standard error of R (and T) is below this (default 0.002)")
                   ->check(CLI::PositiveNumber);
    rays->excludes(se);
    cmd->add_option("--max-rays", o->max_rays, "Ray budget per wavelength with --stderr")->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--seed", o->seed, "Random seed (results are identical for any thread count)")->capture_default_str()->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 63));
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--quantities", o->quantities, "Comma list of R, T, A (absorptance per layer), brdf (angular)")->capture_default_str();
    cmd->add_option("--reflector", o->reflector, "Hypodermis reflector on|off (off: light leaving the bottom is transmittance)");
    cmd->add_option("--variant", o->variant, "Model variant: biospec (default) or biospec-2004");
    cmd->add_option("--mode", o->mode,
                    "Solver: biospec (the BioSpec walk), rte (volumetric walk; layers need volumetric_* scattering), "
                    "multipole (layered diffusion) or dipole (semi-infinite diffusion); diffusion needs reduced scattering")
        ->capture_default_str();
    cmd->add_option("--roughness", o->roughness, "Diffusion modes: Beckmann RMS slope of a rough top surface, (0, 2] (default smooth)")
        ->check(CLI::Range(1e-6, 2.0));
    cmd->add_option("--estimator", o->estimator, "Absorption estimator: weighted (default) or random (the original per-crossing test)")
        ->capture_default_str();
    cmd->add_option("--fold-into-skin", o->fold_into_skin, "Fold-perturbed reflections pointing into the skin: drop (2004 code) or resample")
        ->capture_default_str();
    cmd->add_option("--output", o->output, "Write the result to FILE.csv or FILE.json");
    cmd->add_option("--plot", o->plot, "Plot R (and T) with +-2 standard-error bands to FILE.png or FILE.svg");
    cmd->add_flag("--overwrite,--force", o->force, "Replace the --output / --plot files if they exist");
    cmd->add_flag("--json", o->json, "Print the JSON result on standard output");
    cmd->add_option("--illuminant", o->illuminant, "Illuminant for the colour summary: D65, D50, A, E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "Observer for the colour summary: 2 or 10")->capture_default_str();
    cmd->callback([o] { run_spectrum(*o); });
}

}  // namespace skinspec::cli
