// `skinspec export lut`: a melanosome-fraction x blood-fraction look-up texture of diffuse skin albedo (as the

// maps of Jimenez et al. 2010 and Donner & Jensen 2006 are indexed), computed by the swatch engine
// (appearance/swatch_chart.hpp: the registry's solver, replayed in chunks, each texel to a CIEDE2000 target).
#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "appearance/swatch_chart.hpp"
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

using Json = nlohmann::ordered_json;

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

constexpr const char* melanin_field = "epidermis.melanosome_fraction";
constexpr const char* blood_field = "dermis.blood_fraction";

ParameterSweep lut_axis(const std::string& field, const std::string& text, const std::string& option) {
    try {
        return parse_sweep(field + "=" + text);
    } catch (const InputError& e) {
        throw InputError(option + " " + text + ": " + e.what() + " (FIRST:LAST:STEPS[:log])");
    }
}

std::string value_list(const ParameterSweep& sweep) {
    std::string out;
    for (const double v : sweep.values()) out += (out.empty() ? "" : ",") + format_number(v);
    return out;
}

// Channel name of a reflectance sample in the OpenEXR spectral layout of Fichet, Pacanowski & Wilkie 2021
// (JCGT 10(3), Sec. 3): "T." + wavelength with a comma as decimal separator + "nm".
std::string spectral_channel(double nm) {
    auto text = format_number(nm);
    std::replace(text.begin(), text.end(), '.', ',');
    return "T." + text + "nm";
}

std::string spectra_csv(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v, const std::string& material) {
    std::string out = fmt::format("# skinspec {} look-up spectra: material {}, texel (column, row) = ({}, {})\n", version, material, u.field, v.field);
    out += "# units: fractions unitless; R and R_stderr unitless (reflectance in the LUT's geometry); rays per texel\n";
    out += "column,row," + u.field + "," + v.field + ",delta_e_uncertainty,L_uncertainty,a_uncertainty,b_uncertainty,rays,converged";
    for (const double nm : chart.wavelengths.nm()) out += fmt::format(",R_{}nm", format_number(nm));
    for (const double nm : chart.wavelengths.nm()) out += fmt::format(",R_stderr_{}nm", format_number(nm));
    out += '\n';
    for (std::size_t i = 0; i < chart.patches.size(); ++i) {
        const auto& p = chart.patches[i];
        out += fmt::format("{},{},{},{},{:.4g},{:.4g},{:.4g},{:.4g},{},{}", i % chart.columns, i / chart.columns, format_number(p.parameters[0]),
                           format_number(p.parameters[1]), p.uncertainty.delta_e2000, p.uncertainty.lab.L, p.uncertainty.lab.a, p.uncertainty.lab.b,
                           p.rays, p.converged ? 1 : 0);
        for (const double r : p.reflectance) out += fmt::format(",{:.9g}", r);
        for (const double s : p.reflectance_stderr) out += fmt::format(",{:.3g}", s);
        out += '\n';
    }
    return out;
}

DataImage spectra_image(const SwatchChart& chart) {
    DataImage image;
    image.width = static_cast<int>(chart.columns);
    image.height = static_cast<int>(chart.rows);
    image.channels = static_cast<int>(chart.wavelengths.size());
    image.floating_point = true;
    for (const double nm : chart.wavelengths.nm()) image.channel_names.push_back(spectral_channel(nm));
    image.values.assign(static_cast<std::size_t>(image.width) * image.height * image.channels, 0.0f);
    for (std::size_t i = 0; i < chart.patches.size(); ++i) {
        for (std::size_t w = 0; w < chart.wavelengths.size(); ++w) {
            image.values[i * chart.wavelengths.size() + w] = static_cast<float>(chart.patches[i].reflectance[w]);
        }
    }
    return image;
}

// Every `every`-th value labelled, the others blank (64 labels do not fit above 64 texels); the axis ends are in
// the texture's metadata.
std::vector<std::string> sparse_labels(const ParameterSweep& sweep, std::size_t every) {
    std::vector<std::string> out;
    const auto values = sweep.values();
    for (std::size_t i = 0; i < values.size(); ++i) {
        out.push_back(i % every == 0 ? fmt::format("{:.3g}", values[i]) : std::string());
    }
    return out;
}

void run_export_lut(const LutOptions& o) {
    if (o.output.empty()) throw InputError("export lut: give -o FILE.exr (the linear texture)");
    SwatchRequest request;
    request.material = chosen_material(o.preset, o.material_file);
    request.overrides = parsed_overrides(o.overrides);
    const auto u = lut_axis(melanin_field, o.melanin, "--melanin");
    const auto v = lut_axis(blood_field, o.blood, "--blood");
    request.sweeps = {u, v};
    request.illuminant = parse_illuminant(o.illuminant, "--illuminant");
    request.observer = parse_observer(o.observer, "--observer");
    request.delta_e = o.delta_e;
    request.seed = o.seed;
    request.sampling_options = o.sampling_given;
    request.max_rays_per_wavelength = o.max_rays;
    request.solver = std::string(chosen_solver(o.solver).name());
    request.switches = solver_switches(o.solver);
    request.geometry = measurement_geometry(o.solver);
    request.work_share = process_work_share();

    // Every output is checked before any work: nothing is written for a bad request.
    const auto& cm = ColorManagement::builtin();
    const std::string space = cm.canonical_space(o.space, "--space");
    space_chromaticities(space);
    const ChartLayout texture{u.steps, v.steps, 1, 0};
    check_chart_size(texture);
    const ChartLayout preview{u.steps, v.steps, std::max(8, static_cast<int>(512 / std::max(u.steps, v.steps))), 0};
    cm.check_display_view(o.display, o.view);
    check_output_path(o.output, o.overwrite, {".exr"});
    if (!o.spectra.empty()) check_output_path(o.spectra, o.overwrite, {".exr", ".csv"});
    if (!o.preview.empty()) {
        check_output_path(o.preview, o.overwrite, {".png", ".tif", ".tiff"});
        check_chart_size(preview);
    }
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

    std::vector<RGB> albedo;
    std::uint64_t rays = 0;
    double worst = 0.0;
    for (const auto& p : chart.patches) {
        albedo.push_back(cm.from_xyz(p.xyz, chart.white, space));
        rays += p.rays;
        worst = std::max(worst, p.uncertainty.delta_e2000);
    }
    ImageMetadata metadata{{"Software", std::string("skinspec ") + version},
                           {"skinspec:content", "diffuse albedo: the colour of R (" + std::string(to_string(request.geometry)) +
                                                    ") under the illuminant, white = 1"},
                           {"skinspec:material", request.material},
                           {"skinspec:model", request.solver},
                           {"skinspec:u_field", u.field},
                           {"skinspec:u_values", value_list(u)},
                           {"skinspec:u_spacing", u.log ? "log" : "linear"},
                           {"skinspec:v_field", v.field},
                           {"skinspec:v_values", value_list(v)},
                           {"skinspec:v_spacing", v.log ? "log" : "linear"},
                           {"skinspec:v_direction", "row 0 (top) is the first value"},
                           {"skinspec:seed", std::to_string(request.seed)},
                           {"skinspec:worst_delta_e_uncertainty", fmt::format("{:.4g}", worst)},
                           {"skinspec:partial", chart.partial ? "true" : "false"}};
    for (const auto& ov : request.overrides) metadata.push_back({"skinspec:set " + ov.key, ov.value});
    for (const auto& [k, value] : chart.settings) {
        metadata.push_back({"skinspec:" + k, std::visit([](const auto& x) { return fmt::format("{}", x); }, value)});
    }
    metadata.push_back({"ImageDescription", fmt::format("skinspec look-up texture: {}; columns {} ({}), rows {} ({})", request.material, u.field,
                                                        value_list(u), v.field, value_list(v))});

    write_linear_chart(o.output, texture, albedo, space, o.half, metadata, cm);
    std::cerr << "wrote " << o.output << '\n';
    if (!o.spectra.empty()) {
        if (o.spectra.ends_with(".csv")) {
            write_text_file(o.spectra, spectra_csv(chart, u, v, request.material), o.overwrite);
        } else {
            auto spectral_metadata = metadata;
            spectral_metadata.push_back({"spectralLayoutVersion", "1.0"});
            spectral_metadata.push_back({"skinspec:content", "reflectance spectra, one channel per wavelength"});
            write_atomically(o.spectra, [&](const std::filesystem::path& temporary) {
                write_data_image(temporary, spectra_image(chart), spectral_metadata);
            });
        }
        std::cerr << "wrote " << o.spectra << '\n';
    }
    if (!o.preview.empty()) {
        const ChartAxes axes{u.field + (u.log ? " (log spacing)" : ""), sparse_labels(u, 8), v.field + (v.log ? " (log spacing)" : ""),
                             sparse_labels(v, 8)};
        write_display_chart(o.preview, preview, albedo, {}, space, o.display, o.view, metadata, cm, axes);
        std::cerr << "wrote " << o.preview << '\n';
    }

    if (o.json) {
        std::cout << Json{{"skinspec_version", version}, {"material", request.material}, {"columns", chart.columns}, {"rows", chart.rows},
                          {"space", space}, {"partial", chart.partial}, {"delta_e_target", request.delta_e},
                          {"worst_delta_e_uncertainty", worst}, {"rays", rays}, {"seconds", seconds}, {"processes", process_count()}}
                         .dump(2)
                  << '\n';
    } else {
        std::cout << fmt::format("{} x {} texels ({} x {}), {} rays in {:.2f} s on {} process(es); colour uncertainty (CIEDE2000, RMS) at "
                                 "most {:.3f} (target {}); {} {}{}\n",
                                 chart.columns, chart.rows, u.field, v.field, rays, seconds, process_count(), worst, request.delta_e,
                                 space, to_string(request.geometry),
                                 chart.partial ? fmt::format("; PARTIAL (interrupted): {} of {} texels", chart.patches.size(), chart.columns * chart.rows)
                                               : std::string());
    }
    if (chart.partial) std::exit(InterruptGuard::exit_code());
}

}  // namespace

void add_export_lut_command(CLI::App& exporter) {
    auto o = std::make_shared<LutOptions>();
    o->solver.geometry = "sce";
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
    cmd->add_option("--max-rays", o->max_rays, "Ray budget per wavelength and texel")->capture_default_str()->check(CLI::PositiveNumber);
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
