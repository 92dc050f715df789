#include "cli/fit_image_command.hpp"

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "appearance/lut_export.hpp"
#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "inverse/image_fit/skin_image_fit.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

struct FitImageOptions {
    std::string image;
    std::string output;
    std::string space = "Linear Rec.709";
    std::string bands;
    std::vector<double> white{1.0};
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    std::string melanin = "0.005:0.45:24:log";
    std::string blood = "0.001:0.1:16:log";
    std::string illuminant = "D65";
    std::string observer = "2";
    double delta_e = 0.5;
    std::optional<double> noise;
    double gamut_sigma = 4.0;
    std::vector<std::string> edits;
    std::string edited;
    std::string display = "sRGB";
    std::string view = "Standard";
    std::uint64_t seed = 1;
    std::vector<std::string> sampling_given;
    std::vector<std::string> colour_given;  // --space, --illuminant, --observer, --display, --view, --geometry as given
    std::uint64_t max_rays = 1'000'000;
    unsigned threads = 0;
    bool overwrite = false;
    bool json = false;
    SolverOptions solver;
};

void print_summary(const nlohmann::ordered_json& s, const std::string& u_field, const std::string& v_field) {
    const auto& pixels = s["pixels"];
    const double total = static_cast<double>(s["width"].get<int>()) * s["height"].get<int>();
    const auto share = [&](const char* status) {
        const auto n = pixels[status].get<std::size_t>();
        return fmt::format("{} ({:.1f} %)", n, total > 0 ? 100.0 * static_cast<double>(n) / total : 0.0);
    };
    const auto channels = s["space"].is_null() ? fmt::format("{} bands", s["channels"].size()) : "linear RGB in " + s["space"].get<std::string>();
    std::cout << fmt::format("{} x {} pixels ({}) in {:.2f} s ({:.2f} s for the model's table: {} nodes by {}, colour uncertainty at most CIEDE2000 "
                             "{:.2f})\n",
                             s["width"].get<int>(), s["height"].get<int>(), channels, s["seconds"].get<double>(), s["table_seconds"].get<double>(),
                             s["table_nodes"].get<std::size_t>(), s["model"].get<std::string>(), s["table_worst_delta_e_uncertainty"].get<double>());
    std::cout << fmt::format("fitted {}; outside the model's gamut {}; on the table's edge {}; invalid {}{}\n", share("fitted"),
                             share("outside the model's gamut"), share("on the table's edge"), share("invalid (negative, not finite or black)"),
                             s["partial"].get<bool>() ? "; not fitted (stopped) " + share("not fitted (stopped)") : std::string());
    std::cout << fmt::format("noise {:.3g} per channel ({}); median residual {:.3g}\n", s["noise"].get<double>(),
                             s["noise_estimated"].get<bool>() ? "estimated from the residuals" : "given", s["median_residual"].get<double>());
    for (const auto& f : {u_field, v_field}) {
        const auto& q = s[f];
        std::cout << fmt::format("{}: median {:.4g} (25-75 %: {:.4g} to {:.4g}), median uncertainty {:.2g}\n", f, q["median"].get<double>(),
                                 q["p25"].get<double>(), q["p75"].get<double>(), q["median_stderr"].get<double>());
    }
}

void run_fit_image(const FitImageOptions& o) {
    const auto& cm = ColorManagement::builtin();
    // Everything is checked before the table is computed: nothing is written for a bad request.
    check_output_path(o.output, o.overwrite, {".exr"});
    SkinImageRequest request;
    request.white = o.white;
    const bool multispectral = !o.bands.empty();
    // Options that would be ignored are refused.
    const auto given = [&](const std::string& name) { return std::find(o.colour_given.begin(), o.colour_given.end(), name) != o.colour_given.end(); };
    for (const char* name : {"--space", "--illuminant", "--observer"}) {
        if (multispectral && given(name)) throw InputError(std::string(name) + " describes an RGB image's colour; with --bands the channels are the bands' reflectance factors");
    }
    for (const char* name : {"--display", "--view"}) {
        if (given(name) && (o.edited.empty() || o.edited.ends_with(".exr"))) throw InputError(std::string(name) + " applies to a PNG or TIFF --edited image only");
    }
    if (!multispectral) request.space = cm.canonical_space(o.space, "--space");
    const auto u = lut_axis(lut_melanin_field, o.melanin, "--melanin");
    const auto v = lut_axis(lut_blood_field, o.blood, "--blood");
    request.table.sweeps = {u, v};
    for (const auto& e : o.edits) request.edits.push_back(parse_field_edit(e, u.field, v.field));
    if (request.edits.empty() != o.edited.empty()) {
        throw InputError(request.edits.empty() ? "--edited FILE needs at least one --edit" : "--edit needs --edited FILE (where the re-rendered albedo goes)");
    }
    if (!o.edited.empty()) {
        check_output_path(o.edited, o.overwrite, multispectral ? std::vector<std::string>{".exr"} : std::vector<std::string>{".exr", ".png", ".tif", ".tiff"});
        if (!o.edited.ends_with(".exr")) cm.check_display_view(o.display, o.view);
        if (std::filesystem::absolute(o.edited) == std::filesystem::absolute(o.output)) throw InputError("--edited and -o name the same file: " + o.edited);
    }
    if (multispectral) request.bands = read_band_sensitivities(o.bands);
    request.fit.noise = o.noise;
    request.fit.gamut_sigma = o.gamut_sigma;
    const auto image = read_skin_image(o.image, request);
    // An image skinspec wrote states how it was made: fitted so unless --space / --geometry say otherwise (a stated space
    // is a float image's, whose values are read as they are, in whichever space).
    const auto& stated = image.stated;
    const bool space_stated = !multispectral && !given("--space") && stated.space;
    const bool geometry_stated = !given("--geometry") && stated.geometry;
    if (space_stated) request.space = *stated.space;
    auto solver_options = o.solver;
    if (geometry_stated) solver_options.geometry = to_string(*stated.geometry);
    if (space_stated || geometry_stated) {
        std::cerr << fmt::format("skinspec: note: {} states {}{}{} (skinspec wrote it): fitted so; --space / --geometry override\n", o.image,
                                 space_stated ? "its colour space " + request.space : std::string(), space_stated && geometry_stated ? " and " : "",
                                 geometry_stated ? "geometry " + solver_options.geometry : std::string());
    }

    auto& table = request.table;
    table.material = chosen_material(o.preset, o.material_file);
    table.overrides = parsed_overrides(o.overrides);
    table.illuminant = parse_illuminant(o.illuminant, "--illuminant");
    table.observer = parse_observer(o.observer, "--observer");
    table.delta_e = o.delta_e;
    table.seed = o.seed;
    table.sampling_options = o.sampling_given;
    table.max_rays_per_wavelength = o.max_rays;
    const auto& solver = chosen_solver(o.solver, "biospec-adding-doubling");
    table.solver = std::string(solver.name());
    table.switches = solver_switches(o.solver);
    table.geometry = measurement_geometry(solver_options, solver);

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    table.cancel = &InterruptGuard::cancel_flag();
    request.fit.cancel = table.cancel;
    ProgressBar table_bar("fit-image: the model's table", "nodes"), fit_bar("fit-image", "rows");
    table.on_progress = [&table_bar](std::size_t done, std::size_t total) { table_bar(Progress{0, 0, done, total}); };
    request.fit.on_progress = [&table_bar, &fit_bar](std::size_t done, std::size_t total) {
        table_bar.clear();
        fit_bar(Progress{0, 0, done, total});
    };
    const auto result = fit_skin_image(request, image);
    table_bar.clear();
    fit_bar.clear();
    print_warning_summary(table.material, result.warnings);
    if (result.table_partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << " while computing the model's table: nothing was fitted or written\n";
        std::exit(InterruptGuard::exit_code());
    }
    const auto metadata = skin_image_metadata(result, request, o.image);
    write_data_image(o.output, skin_image_maps(result), metadata);
    std::cerr << "wrote " << o.output << '\n';
    if (result.edited) {
        auto edited = result.edited->values;
        const int width = image.width, height = image.height;
        auto edited_metadata = metadata;
        edited_metadata.push_back({"skinspec:content", "the image re-rendered after the edits " + fmt::format("{}", fmt::join(o.edits, ", ")) +
                                                           " (fitted pixels only)"});
        if (multispectral) {
            write_data_image(o.edited, DataImage{width, height, static_cast<int>(request.bands->names.size()), std::move(edited), true, request.bands->names, {}},
                             edited_metadata);
        } else if (o.edited.ends_with(".exr")) {
            write_linear_image(o.edited, LinearImage{width, height, std::move(edited)}, request.space, false, edited_metadata, cm);
        } else {
            write_display_image(o.edited, LinearImage{width, height, std::move(edited)}, request.space, o.display, o.view, edited_metadata, cm);
        }
        if (result.edited->beyond_table > 0) {
            std::cerr << fmt::format("skinspec: warning: --edit left {} of {} fitted pixels unchanged: their edited fields fall outside the table "
                                     "(--melanin {}, --blood {}); widen it to edit them\n",
                                     result.edited->beyond_table, result.edited->beyond_table + result.edited->rendered, o.melanin, o.blood);
        }
        std::cerr << "wrote " << o.edited << '\n';
    }
    const auto summary = skin_image_summary_json(result, request, o.image);
    if (o.json) std::cout << summary.dump(2) << '\n';
    else print_summary(summary, u.field, v.field);
    if (result.fit.partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": the rows fitted so far were written (the rest status 4); no edit rendered\n";
        std::exit(InterruptGuard::exit_code());
    }
}

}  // namespace

void add_fit_image_command(CLI::App& app) {
    auto o = std::make_shared<FitImageOptions>();
    o->solver.geometry = to_string(image_geometry);
    auto* cmd = app.add_subcommand("fit-image",
                                   "Melanosome and blood maps of a skin albedo image (RGB or multispectral) through the skin model, with "
                                   "uncertainties, residuals, a mask of what is not skin, and edits re-rendered (docs/FIT_IMAGE.md)");
    cmd->add_option("image", o->image,
                    "Albedo image: a linear OpenEXR in --space, or an 8/16-bit PNG, JPEG or TIFF (sRGB-encoded, decoded through OpenColorIO); "
                    "with --bands a multispectral image, one channel per band")
        ->required();
    cmd->add_option("-o,--output", o->output,
                    "The maps (OpenEXR): the two fields, their standard uncertainties (.stderr), the RMS residual and the status per pixel "
                    "(0 fitted, 1 outside the model's gamut, 2 on the table's edge, 3 invalid, 4 not fitted)")
        ->required();
    cmd->add_option("--space", o->space, "Linear colour space of a float image and of the fit (an OCIO colour space)")->capture_default_str();
    cmd->add_option("--bands", o->bands, "Band sensitivities (CSV: wavelength_nm,BAND,...): the image is multispectral, one channel per band");
    cmd->add_option("--white", o->white, "The image value of a perfect white diffuser (the albedo's calibration): one value, or one per channel "
                                         "(R,G,B: a white balance)")
        ->delimiter(',')
        ->capture_default_str();
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    cmd->add_option("--melanin", o->melanin, "The table's epidermis.melanosome_fraction values: FIRST:LAST:STEPS[:log]")->capture_default_str();
    cmd->add_option("--blood", o->blood, "The table's dermis.blood_fraction values: FIRST:LAST:STEPS[:log]")->capture_default_str();
    cmd->add_option("--illuminant", o->illuminant, "Illuminant of the RGB albedo: D65, D50, A or E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "Observer of the RGB albedo: 2 or 10")->capture_default_str();
    cmd->add_option("--delta-e", o->delta_e, "Colour tolerance of a Monte Carlo table (and 5 nm wavelengths below 1, else 10 nm)")->capture_default_str();
    cmd->add_option("--noise", o->noise, "Standard deviation of each channel value (white = 1); default: estimated from the residuals (more than 2 channels)");
    cmd->add_option("--gamut-sigma", o->gamut_sigma, "A pixel whose residual exceeds this many noise sigmas is outside the model's gamut")->capture_default_str();
    cmd->add_option("--edit", o->edits, "FIELD=*SCALE or FIELD=VALUE (repeatable): re-render the fitted pixels with the field changed");
    cmd->add_option("--edited", o->edited, "Where the re-rendered image goes: .exr (linear, --space), .png or .tif (through --display/--view)");
    cmd->add_option("--display", o->display, "OCIO display of a PNG/TIFF --edited")->capture_default_str();
    cmd->add_option("--view", o->view, "OCIO view of a PNG/TIFF --edited")->capture_default_str();
    add_seed_option(*cmd, o->seed, "Random seed (a Monte Carlo table)");
    add_ray_count_option(*cmd, "--max-rays", o->max_rays, "Ray budget per wavelength and node (a Monte Carlo table)")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->add_flag("--json", o->json, "Print the summary as JSON");
    add_solver_options(*cmd, o->solver, "biospec-adding-doubling");
    add_geometry_option(*cmd, o->solver);
    cmd->callback([o, cmd] {
        o->sampling_given = given_sampling_options(*cmd);
        o->colour_given = given_options(*cmd, {"--space", "--illuminant", "--observer", "--display", "--view", "--geometry"});
        run_fit_image(*o);
    });
}

}  // namespace skinspec::cli
