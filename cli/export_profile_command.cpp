// `skinspec export profile`: a material's radial diffuse reflectance R(r) from a registered solver that computes

// profiles, fitted as a sum of Gaussians (inverse/gaussian_sum/gaussian_sum_fit.hpp) per colour band (the
// profile's colour at each radius, in a linear RGB space) or per wavelength, as JSON and a table.
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/common_options.hpp"
#include "cli/export_command.hpp"
#include "cli/material_options.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "inverse/gaussian_sum/gaussian_sum_fit.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/colorimetry.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct ProfileExportOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    SolverOptions solver;
    std::string channels = "rgb";  // --per
    std::string wavelengths = "450,550,650";
    std::string space = "ACEScg";
    std::string illuminant = "D65";
    std::string observer = "2";
    std::size_t gaussians = 6;
    std::string radii = "0:10:0.01";
    std::string output;
    std::string table;
    bool overwrite = false;
    std::uint64_t rays = 0;
    std::uint64_t seed = 1;
    std::vector<std::string> sampling_given;  // --seed, --max-rays as given (refused by deterministic solvers)
};

struct FittedChannels {
    std::vector<std::string> names;
    std::vector<std::vector<double>> profiles_per_mm2;
    std::vector<double> total_reflectance;  // the solver's total diffuse R (the whole plane)
};

// The colour of the profile at each radius: R(r, lambda) integrated against the observer under the illuminant
// (white = 1, so the channel integrates to the diffuse albedo), in the linear RGB space `space`.
FittedChannels rgb_channels(const SpectralProfiles& p, const std::vector<double>& nm, const std::string& space, IlluminantKind illuminant,
                            ObserverKind observer) {
    const auto& cm = ColorManagement::builtin();
    const TristimulusWeights weights(nm, illuminant, observer, OutOfRangePolicy::hold);
    FittedChannels out{{"R", "G", "B"}, std::vector<std::vector<double>>(3), {}};
    std::vector<double> at(nm.size()), totals(nm.size());
    for (std::size_t k = 0; k < p.radii_mm.size(); ++k) {
        for (std::size_t w = 0; w < nm.size(); ++w) at[w] = p.channels[w].reflectance_per_mm2[k];
        const auto rgb = cm.from_xyz(weights.integrate(at), weights.white(), space);
        for (std::size_t c = 0; c < 3; ++c) out.profiles_per_mm2[c].push_back(rgb[c]);
    }
    for (std::size_t w = 0; w < nm.size(); ++w) totals[w] = p.channels[w].total_reflectance;
    const auto total = cm.from_xyz(weights.integrate(totals), weights.white(), space);
    out.total_reflectance.assign(total.begin(), total.end());
    return out;
}

FittedChannels own_channels(const SpectralProfiles& p) {
    FittedChannels out;
    for (const auto& c : p.channels) {
        out.names.push_back(c.label);
        out.profiles_per_mm2.push_back(c.reflectance_per_mm2);
        out.total_reflectance.push_back(c.total_reflectance);
    }
    return out;
}

std::string table_csv(const GaussianSumFit& fit, const FittedChannels& channels, const std::string& header) {
    std::string out = header + "# units: variance_mm2 [mm^2]; weights unitless (each Gaussian integrates to 1 over the plane)\n";
    out += "variance_mm2";
    for (const auto& n : channels.names) out += ",weight_" + n;
    out += '\n';
    for (std::size_t i = 0; i < fit.variances_mm2.size(); ++i) {
        out += fmt::format("{:.9g}", fit.variances_mm2[i]);
        for (const auto& w : fit.weights) out += fmt::format(",{:.9g}", w[i]);
        out += '\n';
    }
    return out;
}

void run_export_profile(const ProfileExportOptions& o) {
    const std::string name = chosen_material(o.preset, o.material_file);
    if (o.channels != "rgb" && o.channels != "wavelength") {
        throw InputError("--per: '" + o.channels + "' is not what to fit per (allowed: rgb, wavelength)");
    }
    const auto& solver = chosen_solver(o.solver, "multipole");
    const auto radii = parse_radii_mm(o.radii, "--radii");
    const auto& cm = ColorManagement::builtin();
    const std::string space = cm.canonical_space(o.space, "--space");
    space_chromaticities(space);
    const auto illuminant = parse_illuminant(o.illuminant, "--illuminant");
    const auto observer = parse_observer(o.observer, "--observer");
    if (!o.output.empty()) check_output_path(o.output, o.overwrite, {".json"});
    if (!o.table.empty()) check_output_path(o.table, o.overwrite, {".csv"});
    const auto material = load_material(name, parsed_overrides(o.overrides));
    const bool bands = std::holds_alternative<HomogeneousMaterial>(material);
    if (bands && o.channels == "wavelength") throw InputError("--per wavelength: material '" + name + "' is given per band; it has no wavelengths");
    // RGB from spectra needs the visible range (CIE 015:2018 Sec. 7.1: 380-780 nm, here every 10 nm).
    const auto grid = o.channels == "rgb" ? WavelengthGrid::range(380.0, 780.0, 10.0) : WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    check_gaussian_count(o.gaussians);

    const auto profiles = solve_profiles(solver, material, profile_request(grid, radii, false, o.solver, o.rays, o.seed, o.sampling_given));
    print_warning_summary(profiles.material, profiles.warnings);
    const auto channels = bands || o.channels == "wavelength" ? own_channels(profiles) : rgb_channels(profiles, {grid.nm().begin(), grid.nm().end()}, space, illuminant, observer);
    const auto fit = fit_gaussian_sum(GaussianSumRequest{radii, channels.profiles_per_mm2, o.gaussians, channels.total_reflectance});

    const std::string what = bands ? "bands" : (o.channels == "rgb" ? "RGB in " + space + " (" + std::string(short_name(illuminant)) + ", " +
                                                                          std::string(short_name(observer)) + ")"
                                                                    : "wavelengths");
    Json channel_json = Json::array();
    for (std::size_t c = 0; c < channels.names.size(); ++c) {
        const double total = channels.total_reflectance[c];
        Json entry;
        entry["name"] = channels.names[c];
        entry["weights"] = fit.weights[c];
        entry["total_reflectance_fit"] = fit.fitted_total[c];
        entry["total_reflectance_model"] = total;
        entry["total_reflectance_relative_error"] = total != 0.0 ? (fit.fitted_total[c] - total) / total : 0.0;
        entry["total_reflectance_profile_range"] = fit.profile_total[c];
        entry["profile_relative_l2_error"] = fit.relative_l2_error[c];
        channel_json.push_back(std::move(entry));
    }
    Json document;
    document["skinspec_version"] = version;
    document["kind"] = "sum of Gaussians: R(r) = sum_i w_i exp(-r^2 / (2 v_i)) / (2 pi v_i)";
    document["reference"] = "d'Eon, Luebke & Enderton 2007; d'Eon & Luebke, GPU Gems 3 ch. 14";
    document["material"] = name;
    document["model"] = profiles.model;
    document["channels"] = what;
    document["radii_mm"] = {{"first", radii.front()}, {"last", radii.back()}, {"count", radii.size()}};
    document["variances_mm2"] = fit.variances_mm2;
    document["fit"] = channel_json;
    document["units"] = {{"variances", "mm^2"}, {"r", "mm"}, {"R(r)", "1/mm^2"}, {"weights", "unitless"}};
    const std::string header = fmt::format("# skinspec {} sum-of-{}-Gaussians fit of R(r): material {}, model {}, channels {}, r {}-{} mm\n", version,
                                           o.gaussians, name, profiles.model, what, format_number(radii.front()), format_number(radii.back()));
    if (!o.output.empty()) {
        write_text_file(o.output, document.dump(2) + "\n", o.overwrite);
        std::cerr << "wrote " << o.output << '\n';
    }
    if (!o.table.empty()) {
        write_text_file(o.table, table_csv(fit, channels, header), o.overwrite);
        std::cerr << "wrote " << o.table << '\n';
    }
    if (o.output.empty()) {
        std::cout << document.dump(2) << '\n';
        return;
    }
    std::cout << header;
    std::cout << fmt::format("{:>14}", "variance mm^2");
    for (const auto& n : channels.names) std::cout << fmt::format("{:>12}", n);
    std::cout << '\n';
    for (std::size_t i = 0; i < fit.variances_mm2.size(); ++i) {
        std::cout << fmt::format("{:>14.5g}", fit.variances_mm2[i]);
        for (const auto& w : fit.weights) std::cout << fmt::format("{:>12.5g}", w[i]);
        std::cout << '\n';
    }
    for (std::size_t c = 0; c < channels.names.size(); ++c) {
        const double total = channels.total_reflectance[c];
        std::cout << fmt::format("{}: profile error (relative L2, r dr) {:.3g} %; total R fit {:.5f} vs model {:.5f} ({:+.3g} %)\n", channels.names[c],
                                 100.0 * fit.relative_l2_error[c], fit.fitted_total[c], total,
                                 total != 0.0 ? 100.0 * (fit.fitted_total[c] - total) / total : 0.0);
    }
}

}  // namespace

void add_export_profile_command(CLI::App& exporter) {
    auto o = std::make_shared<ProfileExportOptions>();
    auto* cmd = exporter.add_subcommand("profile", "R(r) fitted as a sum of Gaussians with shared variances (d'Eon et al. 2007), JSON and a table");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    add_solver_options(*cmd, o->solver, "multipole");
    cmd->add_option("--per", o->channels, "rgb: one fit per colour band (the profile's colour in linear --space); wavelength: one per --wavelengths")
        ->capture_default_str();
    cmd->add_option("--wavelengths", o->wavelengths, "With --per wavelength: wavelengths (nm)")->capture_default_str();
    cmd->add_option("--space", o->space, "With --per rgb: the linear RGB space of the bands (an OCIO colour space)")->capture_default_str();
    cmd->add_option("--illuminant", o->illuminant, "With --per rgb: D65, D50, A or E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "With --per rgb: 2 or 10")->capture_default_str();
    cmd->add_option("--gaussians", o->gaussians, "Number of Gaussians, [1, 12]")->capture_default_str();
    cmd->add_option("--radii", o->radii, "FIRST:LAST:STEP in mm: where R(r) is fitted")->capture_default_str();
    add_profile_ray_options(*cmd, o->rays, o->seed);
    cmd->add_option("-o,--output", o->output, "JSON file of the fit (default: the JSON on standard output)");
    cmd->add_option("--table", o->table, "CSV table of variances and weights");
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->callback([o, cmd] {
        o->sampling_given = given_sampling_options(*cmd);
        run_export_profile(*o);
    });
}

}  // namespace skinspec::cli
