#include "cli/fit_profile_command.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/common_options.hpp"
#include "cli/spectral_output.hpp"
#include "formats/profile_inputs.hpp"
#include "inverse/profile_fit/profile_fit.hpp"
#include "inverse/profile_fit/synthetic_scene.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/line_plot.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct FitOptions {
    std::string irradiance, exitance, mask, patches, profile, column;
    double pitch_mm = 0.0;
    bool synthetic = false;
    double step_mm = 0.1;
    double eta = 1.3;
    double tikhonov = 0.0;
    bool non_negative = false;
    std::string grid_scattering = "0.01:3:0.01";
    std::string grid_absorption = "0:0.01:0.001";
    bool no_refine = false;
    double total_reflectance = -1.0;
    double fit_from_mm = 0.0;
    std::string output_dir;
    bool overwrite = false;
    bool json = false;
};

ParameterGrid parse_grid(const std::string& text, const std::string& option) {
    const auto [first, last, step] = parse_colon_triple(text, option, "per mm");
    return {first, last, step};
}

void write_outputs(const FitOptions& o, const std::vector<std::string>& names, const std::vector<ProfileFitReport>& reports,
                   const std::optional<PlanarScene>& geometry) {
    namespace fs = std::filesystem;
    const fs::path dir(o.output_dir);
    if (fs::exists(dir) && !fs::is_directory(dir)) throw InputError(o.output_dir + ": exists and is not a folder");
    fs::create_directories(dir);
    const auto& first = reports.front().estimate;
    std::string csv = fmt::format("# skinspec {} fit-profile: R'(d) estimated per bin (Mukaigawa et al. 2009 Eq. 24) and the fitted dipole; 1/mm^2\nd_mm", version);
    for (const auto& n : names) csv += fmt::format(",R_estimate_{0},R_dipole_{0},used_{0}", n);
    csv += '\n';
    for (std::size_t i = 0; i < first.distances_mm.size(); ++i) {
        csv += fmt::format("{:g}", first.distances_mm[i]);
        for (const auto& r : reports) csv += fmt::format(",{:.9g},{:.9g},{}", r.estimate.profile_per_mm2[i], r.fitted_profile[i], r.fitted_bins[i] ? 1 : 0);
        csv += '\n';
    }
    write_text_file((dir / "profile_estimate.csv").string(), csv, o.overwrite);
    std::vector<PlotCurve> curves;
    for (std::size_t c = 0; c < reports.size(); ++c) {
        const auto& r = reports[c];
        const auto style = distinct_series_style(c);
        curves.push_back({"R' estimate " + names[c], r.estimate.distances_mm, r.estimate.profile_per_mm2, {}, style.colour, true, style.marker});
        curves.push_back({fmt::format("dipole {} (s' {:.3f}, a {:.4f})", names[c], r.fit.reduced_scattering_per_mm, r.fit.absorption_per_mm),
                          r.estimate.distances_mm, r.fitted_profile, {}, style.colour, false});
    }
    const auto plot = dir / "profile_fit.png";
    if (fs::exists(plot) && !o.overwrite) throw InputError(plot.string() + ": exists already (use --overwrite to replace it)");
    OutputClaims::claim(plot, o.overwrite);
    write_line_plot(plot, "fit-profile: estimated R'(d) and fitted dipole", "Distance d (mm)", "R (1/mm^2)", curves, {.log_y = true});
    if (geometry) {
        const auto exr = dir / "resynthesised.exr";
        check_output_path(exr, o.overwrite, {".exr"});
        DataImage image{geometry->width, geometry->height, static_cast<int>(reports.size()), {}, true, names, {}};
        for (std::size_t p = 0; p < static_cast<std::size_t>(geometry->width) * geometry->height; ++p) {
            for (const auto& r : reports) image.values.push_back(static_cast<float>(r.synthesised[p]));
        }
        write_data_image(exr, image, {{"Software", std::string("skinspec ") + version}, {"ImageDescription", "fit-profile re-synthesis (Mukaigawa et al. 2009 Eq. 10), exitance per mm^2"}});
    }
}

// The synthetic scene as the image pair a planar fit reads (irradiance per mm^2, exitance per mm^2).
void write_synthetic_inputs(const FitOptions& o, const PlanarScene& s) {
    namespace fs = std::filesystem;
    fs::create_directories(o.output_dir);
    const double area = s.pitch_mm * s.pitch_mm;
    DataImage irradiance{s.width, s.height, 1, {}, true, {"Y"}, {}}, exitance = irradiance;
    for (std::size_t p = 0; p < s.incident.size(); ++p) {
        irradiance.values.push_back(static_cast<float>(s.incident[p] / area));
        exitance.values.push_back(static_cast<float>(s.observed[p]));
    }
    const ImageMetadata metadata{{"Software", std::string("skinspec ") + version}, {"skinspec:pixel_mm", fmt::format("{:g}", s.pitch_mm)}};
    for (const auto& [name, image] : {std::pair{"synthetic_irradiance.exr", &irradiance}, std::pair{"synthetic_exitance.exr", &exitance}}) {
        const auto file = fs::path(o.output_dir) / name;
        check_output_path(file, o.overwrite, {".exr"});
        write_data_image(file, *image, metadata);
    }
}

void run_fit_profile(const FitOptions& o) {
    const int forms = (!o.irradiance.empty() || !o.exitance.empty() ? 1 : 0) + (o.patches.empty() ? 0 : 1) + (o.profile.empty() ? 0 : 1) + (o.synthetic ? 1 : 0);
    if (forms != 1) throw InputError("give exactly one input: --irradiance/--exitance/--pitch, --patches, --profile or --synthetic");
    if ((!o.irradiance.empty()) != (!o.exitance.empty())) throw InputError("--irradiance and --exitance go together");
    ProfileFitOptions options;
    options.step_mm = o.step_mm;
    options.solve = {o.tikhonov, o.non_negative};
    options.dipole.eta = o.eta;
    options.dipole.reduced_scattering_per_mm = parse_grid(o.grid_scattering, "--grid-scattering");
    options.dipole.absorption_per_mm = parse_grid(o.grid_absorption, "--grid-absorption");
    options.dipole.refine = !o.no_refine;
    if (o.total_reflectance >= 0.0) options.dipole.total_diffuse_reflectance = o.total_reflectance;
    options.fit_from_mm = o.fit_from_mm;
    if (!o.output_dir.empty() && !o.overwrite) {
        for (const auto* name : {"profile_estimate.csv", "profile_fit.png", "resynthesised.exr"}) {
            if (std::filesystem::exists(std::filesystem::path(o.output_dir) / name)) {
                throw InputError((std::filesystem::path(o.output_dir) / name).string() + ": exists already (use --overwrite to replace it)");
            }
        }
    }

    std::vector<std::string> names;
    std::vector<ProfileFitReport> reports;
    std::optional<PlanarScene> geometry;
    std::string input;
    if (o.synthetic || !o.irradiance.empty()) {
        std::vector<PlanarScene> scenes;
        if (o.synthetic) {
            scenes.push_back(synthetic_planar_scene({}));
            names.push_back("Y");
            if (!o.output_dir.empty()) write_synthetic_inputs(o, scenes.front());
            input = "synthetic: 64 x 64 patches at 0.05 mm, dipole sigma_s' 2.19, sigma_a 0.002 /mm, eta 1.3";
        } else {
            scenes = read_planar_scenes({o.irradiance, o.exitance, o.mask, o.pitch_mm}, names);
            input = fmt::format("{} and {} ({}x{} px at {:g} mm)", o.irradiance, o.exitance, scenes.front().width, scenes.front().height, o.pitch_mm);
        }
        for (const auto& s : scenes) reports.push_back(fit_planar(s, options));
        geometry = scenes.front();
    } else if (!o.patches.empty()) {
        const auto patches = read_patch_list(o.patches);
        reports.push_back(fit_patches(patches, options));
        names.push_back("l");
        input = fmt::format("{} ({} patches)", o.patches, patches.size());
    } else {
        const auto samples = read_radial_profile(o.profile, o.column);
        if (samples.entry_transmittance != 1.0) {
            std::cerr << fmt::format("skinspec: note: {}: R divided by the entry transmittance {:.6g} the file records (the dipole's R_d(r) is per "
                                     "unit power entering the skin)\n", o.profile, samples.entry_transmittance);
        }
        reports.push_back(fit_radial(samples.radii_mm, samples.profile_per_mm2, options));
        names.push_back(o.column.empty() ? "R" : o.column);
        input = fmt::format("{} ({} radii)", o.profile, samples.radii_mm.size());
    }

    if (!o.output_dir.empty()) write_outputs(o, names, reports, geometry);
    for (std::size_t c = 0; c < reports.size(); ++c) {
        for (const auto& b : reports[c].fit.at_bounds) {
            std::cerr << "skinspec: warning: channel " << names[c] << ": " << b << "\n";
        }
    }
    if (o.json) {
        Json channels = Json::array();
        for (std::size_t c = 0; c < reports.size(); ++c) channels.push_back(profile_fit_json(reports[c], names[c]));
        std::cout << Json{{"skinspec_version", version}, {"input", input}, {"eta", o.eta}, {"step_mm", o.step_mm}, {"channels", channels}}.dump(2) << '\n';
        return;
    }
    std::cout << "input: " << input << "\n";
    std::cout << fmt::format("{:>8} {:>22} {:>24} {:>12} {:>12} {:>10} {:>6} {:>6}\n", "channel", "sigma_s'/mm", "sigma_a/mm", "grid s'",
                             "grid a", "PSNR dB", "bins", "rank");
    const auto with_stderr = [](double value, double stderr, int digits) {
        return fmt::format("{:.{}f} +- {}", value, digits, std::isfinite(stderr) ? fmt::format("{:.2g}", stderr) : std::string("n/a"));
    };
    for (std::size_t c = 0; c < reports.size(); ++c) {
        const auto& r = reports[c];
        std::cout << fmt::format("{:>8} {:>22} {:>24} {:>12.3f} {:>12.4f} {:>10} {:>6} {:>6}\n", names[c],
                                 with_stderr(r.fit.reduced_scattering_per_mm, r.fit.reduced_scattering_stderr_per_mm, 5),
                                 with_stderr(r.fit.absorption_per_mm, r.fit.absorption_stderr_per_mm, 6), r.fit.grid_reduced_scattering_per_mm, r.fit.grid_absorption_per_mm,
                                 r.psnr_db ? fmt::format("{:.2f}", *r.psnr_db) : std::string("-"), r.estimate.distances_mm.size(), r.estimate.rank);
    }
    std::cout << "+-: standard errors from the residual scatter, for independent errors per bin; "
              << (geometry || !o.patches.empty() ? "an image's bins share their errors, so these are lower bounds\n" : "correlated errors make them lower bounds\n");
    if (!o.output_dir.empty()) std::cerr << "wrote " << o.output_dir << "/profile_estimate.csv, profile_fit.png" << (geometry ? ", resynthesised.exr" : "") << '\n';
}

}  // namespace

void add_fit_profile_command(CLI::App& app) {
    auto o = std::make_shared<FitOptions>();
    auto* cmd = app.add_subcommand("fit-profile", "Dipole parameters (sigma_s', sigma_a) from an image with known light, a patch list or R(r)");
    cmd->add_option("--irradiance", o->irradiance, "Planar input: image of the irradiance entering the surface (per mm^2; EXR)");
    cmd->add_option("--exitance", o->exitance, "Planar input: image of the observed exitance pi L_o / F_t (per mm^2; EXR)");
    cmd->add_option("--pitch", o->pitch_mm, "Planar input: pixel pitch in mm");
    cmd->add_option("--mask", o->mask, "Planar input: image whose non-zero pixels are valid observations");
    cmd->add_option("--patches", o->patches, "Patch list CSV: x_mm,y_mm,z_mm,nx,ny,nz,c,l,visible");
    cmd->add_option("--profile", o->profile, "Radial profile CSV: r_mm and R (1/mm^2 per unit power entering) columns; a skinspec profile CSV (per incident power) is divided by the entry transmittance it records");
    cmd->add_option("--column", o->column, "With --profile: the column to fit (default the second)");
    cmd->add_flag("--synthetic", o->synthetic, "Fit the built-in synthetic scene of Mukaigawa et al. 2009 Sec. 4.1 (a demonstration)");
    cmd->add_option("--step", o->step_mm, "Distance quantisation step in mm (Mukaigawa et al. 2009 Eq. 15-16)")->capture_default_str();
    cmd->add_option("--eta", o->eta, "Relative index of refraction")->capture_default_str();
    cmd->add_option("--tikhonov", o->tikhonov, "Tikhonov lambda for r = W+ l (default 0: the paper's pseudo-inverse)")->capture_default_str();
    cmd->add_flag("--non-negative", o->non_negative, "Constrain the estimated profile to R' >= 0");
    cmd->add_option("--grid-scattering", o->grid_scattering, "Grid of sigma_s' (per mm), FIRST:LAST:STEP")->capture_default_str();
    cmd->add_option("--grid-absorption", o->grid_absorption, "Grid of sigma_a (per mm), FIRST:LAST:STEP")->capture_default_str();
    cmd->add_flag("--no-refine", o->no_refine, "Stop at the grid's best (no local optimiser)");
    cmd->add_option("--total-reflectance", o->total_reflectance, "Measured total diffuse reflectance: constrains sigma_a (Jensen et al. 2001 Sec. 3)");
    cmd->add_option("--fit-from", o->fit_from_mm, "Leave distances below this (mm) out of the dipole fit")->capture_default_str();
    cmd->add_option("--output-dir", o->output_dir, "Write profile_estimate.csv, profile_fit.png and resynthesised.exr here");
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->add_flag("--json", o->json, "Print the result as JSON");
    cmd->callback([o] { run_fit_profile(*o); });
}

}  // namespace skinspec::cli
