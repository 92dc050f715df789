// `skinspec export lut`: a melanosome-fraction x blood-fraction look-up texture of diffuse skin albedo, computed by
// the swatch engine (appearance/swatch_chart.hpp: the registry's solver, replayed in chunks, each texel to a
// CIEDE2000 target) and written by appearance/lut_export.hpp.
#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "appearance/lut_export.hpp"
#include "cli/color_output.hpp"
#include "cli/common_options.hpp"
#include "cli/export_command.hpp"
#include "cli/material_options.hpp"
#include "cli/process_group.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

struct LutOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    std::string melanin = "0.01:0.42:64:log";
    std::string blood = "0.002:0.05:64:log";
    std::string illuminant = "D65";
    std::string observer = "2";
    double delta_e = 0.5;
    std::string output;
    std::string space = "ACEScg";
    bool half = false;
    std::string spectra;
    std::string preview;
    std::string display = "sRGB";
    std::string view = "Standard";
    std::uint64_t seed = 1;
    std::vector<std::string> sampling_given;  // --seed, --max-rays as given (refused by deterministic solvers)
    std::uint64_t max_rays = 1'000'000;
    unsigned threads = 0;
    bool overwrite = false;
    bool json = false;
    SolverOptions solver;
};

void run_export_lut(const LutOptions& o) {
    if (o.output.empty()) throw InputError("export lut: give -o FILE.exr (the linear texture)");
    SwatchRequest request;
    request.material = chosen_material(o.preset, o.material_file);
    request.overrides = parsed_overrides(o.overrides);
    const auto u = lut_axis(lut_melanin_field, o.melanin, "--melanin");
    const auto v = lut_axis(lut_blood_field, o.blood, "--blood");
    request.sweeps = {u, v};
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
    request.work_share = process_work_share();

    // Every output is checked before any work: nothing is written for a bad request.
    const auto files = check_lut_files(LutFiles{o.output, o.spectra, o.preview, o.space, o.half, o.display, o.view, o.overwrite}, u, v);
    const bool root = is_root_process();

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    request.cancel = &InterruptGuard::cancel_flag();
    ProgressBar bar("export lut", "texels");
    if (root) request.on_progress = [&bar](std::size_t done, std::size_t total) { bar(Progress{0, 0, done, total}); };
    const auto start = std::chrono::steady_clock::now();
    const auto chart = compute_swatch(request);
    bar.clear();
    if (!root) return;
    print_warning_summary(request.material, chart.warnings);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto summary = write_lut_files(chart, request, files);
    std::cerr << "wrote " << o.output << '\n';
    if (!o.spectra.empty()) std::cerr << "wrote " << o.spectra << '\n';
    if (!o.preview.empty()) std::cerr << "wrote " << o.preview << '\n';

    if (o.json) {
        std::cout << lut_summary_json(chart, request, files, summary, seconds, process_count()).dump(2) << '\n';
    } else {
        std::cout << fmt::format("{} x {} texels ({} x {}), {} rays in {:.2f} s on {} process(es); colour uncertainty (CIEDE2000, RMS) at "
                                 "most {:.3f} ({}); {} {}{}\n",
                                 chart.columns, chart.rows, u.field, v.field, summary.rays, seconds, process_count(), summary.worst_delta_e,
                                 delta_e_target_text(summary.worst_delta_e, request.delta_e, summary.rays), files.space, to_string(request.geometry),
                                 chart.partial ? fmt::format("; PARTIAL (interrupted): {} of {} texels", chart.patches.size(), chart.columns * chart.rows)
                                               : std::string());
    }
    if (chart.partial) std::exit(InterruptGuard::exit_code());
}

}  // namespace

void add_export_lut_command(CLI::App& exporter) {
    auto o = std::make_shared<LutOptions>();
    o->solver.geometry = to_string(image_geometry);
    auto* cmd = exporter.add_subcommand("lut", "Melanosome x blood look-up texture of diffuse skin albedo (linear EXR), spectra and a preview");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    cmd->add_option("--melanin", o->melanin, "epidermis.melanosome_fraction per column: FIRST:LAST:STEPS[:log]")->capture_default_str();
    cmd->add_option("--blood", o->blood, "dermis.blood_fraction per row (top to bottom): FIRST:LAST:STEPS[:log]")->capture_default_str();
    cmd->add_option("--illuminant", o->illuminant, "D65, D50, A or E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "2 or 10")->capture_default_str();
    cmd->add_option("--delta-e", o->delta_e, "Colour tolerance: each texel stops once its CIEDE2000 uncertainty is below")->capture_default_str();
    cmd->add_option("-o,--output", o->output, "The texture: linear OpenEXR, one texel per (melanin, blood)")->required();
    cmd->add_option("--space", o->space, "Working space of the texture (an OCIO colour space, e.g. ACEScg, 'Linear Rec.709')")->capture_default_str();
    cmd->add_flag("--half", o->half, "Write the texture in half float (default float)");
    cmd->add_option("--spectra", o->spectra, "Also write the reflectance spectra: .exr (one channel per wavelength, Fichet et al. 2021 layout) or .csv");
    cmd->add_option("--preview", o->preview, "Also write a display-referred preview with labelled axes: .png or .tif");
    cmd->add_option("--display", o->display, "OCIO display of the preview")->capture_default_str();
    cmd->add_option("--view", o->view, "OCIO view of the preview")->capture_default_str();
    add_seed_option(*cmd, o->seed, "Random seed");
    add_ray_count_option(*cmd, "--max-rays", o->max_rays, "Ray budget per wavelength and texel")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads per process (default: all cores)")->check(CLI::Range(1u, 1024u));
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->add_flag("--json", o->json, "Print the summary as JSON");
    add_solver_options(*cmd, o->solver);
    add_geometry_option(*cmd, o->solver);
    cmd->callback([o, cmd] {
        o->sampling_given = given_sampling_options(*cmd);
        run_export_lut(*o);
    });
}

}  // namespace skinspec::cli
