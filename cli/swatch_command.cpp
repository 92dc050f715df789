#include "cli/swatch_command.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "appearance/lit_swatch.hpp"
#include "appearance/profile_shape_report.hpp"
#include "appearance/swatch_files.hpp"
#include "cli/color_output.hpp"
#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "cli/profile_shape_output.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "materials/material_fields.hpp"
#include "skinspec/version.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct SwatchOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    std::vector<std::string> vary;
    std::string illuminant = "D65";
    std::string observer = "2";
    double delta_e = 0.3;
    bool delta_e_given = false;  // a chart's tolerance: refused with --lit, whose precision is --stderr
    std::vector<std::string> outputs;
    std::string space = "ACEScg";
    bool half = false;
    std::string display = "sRGB";
    std::string view = "Standard";
    int patch_px = 112;
    std::uint64_t seed = 1;
    std::vector<std::string> sampling_given;  // --seed, --max-rays as given (refused by deterministic solvers)
    std::uint64_t max_rays = 1'000'000;
    double stderr_target = default_profile_stderr;  // --lit: the profiles' precision
    unsigned threads = 0;
    bool overwrite = false;
    bool json = false;
    std::vector<std::string> lit;  // spot | edge | pattern FILE
    SolverOptions solver;
    std::string wavelengths = "400:700:10";
    double field_mm = 20.0;
    int pixels = 256;
    double spot_radius_mm = 2.0;
};

// `swatch --lit spot|edge|pattern FILE`: one planar patch under structured light, from radial profiles (default the exact
// transport).
void run_lit_swatch(const SwatchOptions& o) {
    const std::string name = chosen_material(o.preset, o.material_file);
    if (!o.vary.empty()) throw InputError("--vary: a lit swatch shows one material (use --set for its parameters)");
    if (o.outputs.empty()) throw InputError("--lit: give at least one -o FILE (.exr, .png, .tif)");
    if (o.delta_e_given) throw InputError("--delta-e: a chart's colour tolerance; a lit swatch's precision is --stderr");
    const auto& kind = o.lit.front();
    if (kind != "spot" && kind != "edge" && kind != "pattern") {
        throw InputError("--lit: '" + kind + "' is not a lighting (allowed: spot, edge, pattern FILE)");
    }
    if (kind == "pattern" && o.lit.size() != 2) throw InputError("--lit pattern: give the image file, e.g. --lit pattern stripes.png");
    if (kind != "pattern" && o.lit.size() != 1) throw InputError("--lit " + kind + ": takes no file (only pattern does)");
    auto view = lit_view(o.field_mm, o.pixels);
    const auto files = check_image_outputs(ImageOutputs{{o.outputs.begin(), o.outputs.end()}, o.space, o.half, o.display, o.view, o.overwrite});

    const auto overrides = parsed_overrides(o.overrides);
    const auto material = load_material(name, overrides);
    // A lit patch needs radial profiles: the exact transport unless --mode names another solver.
    const auto& solver = chosen_profile_solver(o.solver);
    check_overrides(solver, material, overrides);
    const auto switches = solver_switches(o.solver);
    const auto geometry = measurement_geometry(o.solver, solver);
    const auto illuminant = parse_illuminant(o.illuminant, "--illuminant");
    const auto observer = parse_observer(o.observer, "--observer");
    const auto grid = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    const auto light = kind == "spot" ? Illumination::spot(o.spot_radius_mm)
                       : kind == "edge" ? Illumination::edge()
                                        : pattern_lighting(read_linear_image(o.lit[1], "Linear Rec.709", ColorManagement::builtin()), view);

    const InterruptGuard interrupt;
    ProgressBar bar("lit swatch");
    const auto start = std::chrono::steady_clock::now();
    ProfileRequest settings;
    settings.switches = switches;
    settings.stderr_target = o.stderr_target;
    settings.max_rays_per_wavelength = o.max_rays;
    settings.seed = o.seed;
    settings.sampling_options = o.sampling_given;
    const auto swatch = render_lit_swatch(material, grid, light, view, solver, settings, geometry, illuminant, observer, files.space,
                                          [&bar](std::size_t done, std::size_t total) { bar(Progress{0, 0, done, total}); },
                                          &InterruptGuard::cancel_flag());
    bar.clear();
    if (swatch.patch.partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": nothing written (a lit swatch needs every wavelength)\n";
        std::exit(InterruptGuard::exit_code());
    }
    const auto rendered = std::chrono::steady_clock::now();
    const auto& patch = swatch.patch;
    const auto shape = stated_profile_shape(solver, material, grid, switches, &InterruptGuard::cancel_flag());
    if (shape.stopped) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": nothing written (stopped in the profiles' shape check)\n";
        std::exit(InterruptGuard::exit_code());
    }
    const auto checked = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(checked - start).count();
    const double check_seconds = std::chrono::duration<double>(checked - rendered).count();
    print_profile_summary(patch.profiles, shape);
    write_lit_swatch(swatch, name, light, o.field_mm, o.wavelengths, files, profile_shape_text(shape));
    for (const auto& out : o.outputs) std::cerr << "wrote " << out << '\n';
    const auto lighting = light.description();
    const bool bands = swatch.bands;
    std::cout << fmt::format("{} under {}: {}x{} px at {:g} mm, {} {} in {:.2f} s ({} mode{}); kernel reach {:g} mm, "
                             "largest kernel energy correction {:.2g} %\n",
                             name, lighting, view.width_px, view.height_px, view.pixel_mm, patch.exitance.size(),
                             bands ? "bands" : "wavelengths", seconds, patch.profiles.model,
                             shape.errors.empty() ? std::string() : fmt::format(", of which the R(r) shape check {:.2f} s", check_seconds),
                             patch.kernel_radius_px * view.pixel_mm, 100.0 * patch.largest_kernel_correction);
}

void run_swatch(const SwatchOptions& o) {
    if (!o.lit.empty()) return run_lit_swatch(o);
    if (std::find(o.sampling_given.begin(), o.sampling_given.end(), "--stderr") != o.sampling_given.end()) {
        throw InputError("--stderr: the precision of a lit swatch's profiles (with --lit); a chart's is --delta-e");
    }
    SwatchRequest request;
    request.material = chosen_material(o.preset, o.material_file);
    request.overrides = parsed_overrides(o.overrides);
    if (o.vary.empty()) request.sweeps = default_swatch_sweeps(load_material(request.material, request.overrides));
    for (const auto& v : o.vary) request.sweeps.push_back(parse_sweep(v));
    request.illuminant = parse_illuminant(o.illuminant, "--illuminant");
    request.observer = parse_observer(o.observer, "--observer");
    request.delta_e = o.delta_e;
    request.seed = o.seed;
    request.sampling_options = o.sampling_given;
    request.max_rays_per_wavelength = o.max_rays;
    const auto& solver = chosen_solver(o.solver);
    request.solver = std::string(solver.name());
    request.switches = solver_switches(o.solver);
    request.geometry = measurement_geometry(o.solver, solver);
    // Every output is checked before any work: nothing is written for a bad request.
    const auto files =
        check_swatch_files(SwatchFiles{{{o.outputs.begin(), o.outputs.end()}, o.space, o.half, o.display, o.view, o.overwrite}, o.patch_px}, request);
    const auto& space = files.images.space;
    const auto& cm = ColorManagement::builtin();

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    request.cancel = &InterruptGuard::cancel_flag();
    ProgressBar bar("swatch", "patches");
    request.on_progress = [&bar](std::size_t done, std::size_t total) { bar(Progress{0, 0, done, total}); };

    const auto start = std::chrono::steady_clock::now();
    const auto chart = compute_swatch(request);
    bar.clear();
    print_warning_summary(request.material, chart.warnings);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::vector<RGB> working;
    std::vector<ColorSummary> colours;
    double worst = 0.0;
    const TristimulusWeights weights(chart.wavelengths.nm(), request.illuminant, request.observer, OutOfRangePolicy::hold);
    for (const auto& p : chart.patches) {
        working.push_back(cm.from_xyz(p.xyz, chart.white, space));
        colours.push_back(summarize_color(p.xyz, weights, request.illuminant, request.observer, {}, p.uncertainty));
        worst = std::max(worst, p.uncertainty.delta_e2000);
    }
    write_swatch_files(chart, request, files);
    for (const auto& out : o.outputs) std::cerr << "wrote " << out << '\n';

    std::uint64_t rays = 0;
    for (const auto& p : chart.patches) rays += p.rays;
    if (o.json) {
        Json patches = Json::array();
        for (std::size_t i = 0; i < chart.patches.size(); ++i) {
            const auto& p = chart.patches[i];
            auto c = to_json(colours[i]);
            c["parameters"] = p.parameters;
            c["delta_e_uncertainty"] = p.uncertainty.delta_e2000;
            c["rays"] = p.rays;
            c["converged"] = p.converged;
            c[space] = working[i];
            patches.push_back(c);
        }
        Json fields = Json::array();
        for (const auto& s : request.sweeps) fields.push_back(s.field);
        std::cout << Json{{"skinspec_version", version}, {"material", request.material}, {"fields", fields},
                          {"columns", chart.columns}, {"rows", chart.rows}, {"partial", chart.partial},
                          {"delta_e_target", request.delta_e}, {"worst_delta_e_uncertainty", worst}, {"rays", rays},
                          {"seconds", seconds}, {"patches", patches}}
                         .dump(2)
                  << '\n';
    } else {
        std::cout << fmt::format("{:<28}{:>9}  {:<26}{:<22}{:<24}{:>8}{:>12}\n", "parameters", "sRGB", "Lab", "Lab +-", "ITA deg (category)", "dE unc",
                                 "rays");
        for (std::size_t i = 0; i < chart.patches.size(); ++i) {
            const auto& p = chart.patches[i];
            std::string params;
            for (const double v : p.parameters) params += fmt::format("{:<10.4g}", v);
            const auto& tone = colours[i].skin_tone;
            std::cout << fmt::format("{:<28}{:>9}  {:<26}{:<22}{:<24}{:>8.3f}{:>12}\n", params, colours[i].srgb_hex,
                                     fmt::format("{:.2f} {:.2f} {:.2f}", p.lab.L, p.lab.a, p.lab.b),
                                     fmt::format("{:.2f} {:.2f} {:.2f}", p.uncertainty.lab.L, p.uncertainty.lab.a, p.uncertainty.lab.b),
                                     tone ? fmt::format("{:.1f} ({})", tone->ita_deg, to_string(tone->category)) : std::string("-"),
                                     p.uncertainty.delta_e2000, p.rays);
        }
        const auto target = delta_e_target_text(worst, request.delta_e, rays);
        std::cout << fmt::format("{} patches, {} rays in {:.2f} s; colour uncertainty (CIEDE2000, RMS) at most {:.3f} "
                                 "({}); wavelengths {}{}\n",
                                 chart.patches.size(), rays, seconds, worst, target,
                                 std::get<std::string>(chart.settings.at("wavelengths")), chart.partial ? "; PARTIAL (interrupted)" : "");
    }
    if (chart.partial) std::exit(InterruptGuard::exit_code());
}

}  // namespace

void add_swatch_command(CLI::App& app) {
    auto o = std::make_shared<SwatchOptions>();
    o->solver.geometry = to_string(image_geometry);
    auto* cmd = app.add_subcommand("swatch", "Chart image of simulated skin colours over one or two stack fields");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    cmd->add_option("--vary", o->vary,
                    "FIELD=FIRST:LAST:STEPS[:log], columns then rows (default epidermis.melanosome_fraction=0.01:0.42:8:log and "
                    "dermis.blood_fraction=0.002:0.05:5 for skin stacks; one patch otherwise); ':log' spaces the values evenly in "
                    "their logarithm");
    cmd->add_option("--illuminant", o->illuminant, "D65, D50, A or E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "2 or 10")->capture_default_str();
    cmd->add_option("--delta-e", o->delta_e, "Colour tolerance: each patch stops once its CIEDE2000 uncertainty is below")->capture_default_str();
    cmd->add_option("-o,--output", o->outputs, "Image file .exr (linear), .png or .tif/.tiff (display-referred); repeatable");
    cmd->add_option("--space", o->space, "Working space of the EXR (an OCIO colour space)")->capture_default_str();
    cmd->add_flag("--half", o->half, "Write the EXR in half float (default float)");
    cmd->add_option("--display", o->display, "OCIO display for PNG/TIFF")->capture_default_str();
    cmd->add_option("--view", o->view, "OCIO view for PNG/TIFF")->capture_default_str();
    auto* patch_size = cmd->add_option("--patch-size", o->patch_px, "Patch size in pixels (the chart's; not with --lit)")->capture_default_str();
    add_seed_option(*cmd, o->seed, "Random seed");
    add_ray_count_option(*cmd, "--max-rays", o->max_rays, "Ray budget per wavelength and patch (with --lit: per wavelength)")->capture_default_str();
    cmd->add_option("--stderr", o->stderr_target,
                    "With --lit (rte): each wavelength's profile runs until the standard error of the reflectance leaving within every "
                    "radius of a 1-2-5 series up to the kernel's reach is at most this")
        ->capture_default_str()
        ->check(CLI::Range(1e-6, 0.5));
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->add_flag("--json", o->json, "Print the patches as JSON");
    auto* lit = cmd->add_option("--lit", o->lit,
                                "Render one patch under structured light from radial profiles (default the exact transport): spot, edge, or pattern FILE "
                                "(an image whose luminance is the irradiance)")
                    ->expected(1, 2);
    patch_size->excludes(lit);
    add_solver_options(*cmd, o->solver, std::string("biospec; with --lit ") + profile_solver_default);
    add_geometry_option(*cmd, o->solver);
    // The lit patch's own options: given without --lit (the chart) they would change nothing, so CLI11 refuses them.
    cmd->add_option("--wavelengths", o->wavelengths, "With --lit: wavelengths (nm) for layered materials")->capture_default_str()->needs(lit);
    cmd->add_option("--field", o->field_mm, "With --lit: width of the patch in mm")->capture_default_str()->needs(lit);
    cmd->add_option("--pixels", o->pixels, "With --lit: image width in pixels, [8, 4096]")->capture_default_str()->needs(lit);
    cmd->add_option("--spot-radius", o->spot_radius_mm, "With --lit spot: radius of the lit disc in mm")->capture_default_str()->needs(lit);
    cmd->callback([o, cmd] {
        o->sampling_given = given_options(*cmd, {"--seed", "--max-rays", "--stderr"});
        o->delta_e_given = !given_options(*cmd, {"--delta-e"}).empty();
        run_swatch(*o);
    });
}

}  // namespace skinspec::cli
