// `skinspec export profile`: a material's radial diffuse reflectance R(r) from a registered solver that computes
// profiles, fitted as a sum of Gaussians per colour band or per wavelength (appearance/profile_export.hpp), as JSON
// and a table.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "appearance/profile_shape_report.hpp"
#include "cli/common_options.hpp"
#include "cli/export_command.hpp"
#include "cli/material_options.hpp"
#include "cli/profile_shape_output.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "appearance/profile_export.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "materials/parameter_sweep.hpp"

namespace skinspec::cli {
namespace {

struct ProfileExportOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    SolverOptions solver;
    std::string channels = "rgb";  // --per
    std::string wavelengths;  // --wavelengths as given (empty: not given)
    std::string space = "ACEScg";
    std::string illuminant = "D65";
    std::string observer = "2";
    std::size_t gaussians = 6;
    std::string radii = "0:10:0.01";
    std::string output;
    std::string table;
    bool overwrite = false;
    bool json = false;
    ProfileSampling sampling;
    std::vector<std::string> vary;
};

// The JSON (-o) and the table (--table) where asked for; true when the JSON went to standard output instead of the
// summary (no -o, or --json).
bool write_export(const ProfileExportOptions& o, const nlohmann::ordered_json& document, const std::string& table) {
    if (!o.output.empty()) {
        write_text_file(o.output, document.dump(2) + "\n", o.overwrite);
        std::cerr << "wrote " << o.output << '\n';
    }
    if (!o.table.empty()) {
        write_text_file(o.table, table, o.overwrite);
        std::cerr << "wrote " << o.table << '\n';
    }
    if (!o.output.empty() && !o.json) return false;
    std::cout << document.dump(2) << '\n';
    return true;
}

// A grid (--vary): every member's profile (the exact transport from one walk per wavelength, the exit replay), one set
// of variances for them all, the JSON and the table of every member's weights.
void run_export_profile_grid(const ProfileExportOptions& o, const Material& base, const SpectralSolver& solver, const ProfileRequest& request,
                             const ProfileExportRequest& fit_request, bool bands) {
    std::vector<ParameterSweep> sweeps;
    for (const auto& v : o.vary) sweeps.push_back(parse_sweep(v));
    if (sweeps.size() > 2) throw InputError("--vary: at most two fields (they form a grid); got " + std::to_string(sweeps.size()));
    const auto axes = sweep_axes(sweeps);
    const auto built = profile_grid_members(base, axes);
    std::vector<const Material*> members;
    for (const auto& m : built) members.push_back(&m);
    const auto profiles = solve_profiles_stoppable(solver, members, request, "export profile");
    if (profiles.size() < members.size() || profiles.back().partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": nothing written (the fit needs every member's profile)\n";
        std::exit(InterruptGuard::exit_code());
    }
    if (const auto precision = profile_precision_line(profiles); !precision.empty()) std::cerr << "skinspec: note: " << precision << '\n';
    const auto grid = fit_profile_export_grid(profiles, axes, bands, fit_request);
    const auto document = profile_export_grid_json(grid);
    if (write_export(o, document, profile_export_grid_table_csv(grid))) return;
    // The summary: the shared variances, then the worst member's errors.
    const auto& first = grid.members.front();
    std::cout << profile_export_header(first);
    std::cout << fmt::format("{} members ({}), one set of {} variances (mm^2):", grid.members.size(), o.vary.size() == 1 ? o.vary[0] : o.vary[0] + " x " + o.vary[1],
                             first.fit.variances_mm2.size());
    for (const double v : first.fit.variances_mm2) std::cout << fmt::format(" {:.5g}", v);
    std::cout << '\n';
    double worst_profile = 0.0, worst_total = 0.0;
    std::size_t worst_member = 0;
    for (std::size_t m = 0; m < grid.members.size(); ++m) {
        const auto& e = grid.members[m];
        for (std::size_t c = 0; c < e.names.size(); ++c) {
            if (e.fit.relative_l2_error[c] > worst_profile) {
                worst_profile = e.fit.relative_l2_error[c];
                worst_member = m;
            }
            if (e.total_reflectance[c] != 0.0) worst_total = std::max(worst_total, std::abs(e.fit.fitted_total[c] / e.total_reflectance[c] - 1.0));
        }
    }
    std::cout << fmt::format("worst member: profile error (relative L2, r dr) {:.3g} % (member {}); total R fit within {:.3g} % of the model's at every member\n",
                             100.0 * worst_profile, worst_member, 100.0 * worst_total);
}

void run_export_profile(const ProfileExportOptions& o) {
    const std::string name = chosen_material(o.preset, o.material_file);
    ProfileExportRequest fit_request;
    fit_request.per = parse_profile_channels(o.channels, "--per");
    const auto radii = parse_radii_mm(o.radii, "--radii");
    const auto& cm = ColorManagement::builtin();
    fit_request.space = cm.canonical_space(o.space, "--space");
    space_chromaticities(fit_request.space);
    fit_request.illuminant = parse_illuminant(o.illuminant, "--illuminant");
    fit_request.observer = parse_observer(o.observer, "--observer");
    fit_request.gaussians = o.gaussians;
    if (!o.output.empty()) check_output_path(o.output, o.overwrite, {".json"});
    if (!o.table.empty()) check_output_path(o.table, o.overwrite, {".csv"});
    const auto overrides = parsed_overrides(o.overrides);
    const auto material = load_material(name, overrides);
    const auto& solver = chosen_profile_solver(o.solver);
    const bool bands = std::holds_alternative<HomogeneousMaterial>(material);
    check_profile_export(name, bands, fit_request);
    const auto grid = profile_export_wavelengths(
        fit_request, o.wavelengths.empty() ? std::nullopt : std::optional(WavelengthGrid::parse(o.wavelengths, "--wavelengths")), "--wavelengths");
    if (!o.vary.empty()) {
        run_export_profile_grid(o, material, solver, profile_request(grid, radii, false, o.solver, o.sampling, overrides), fit_request, bands);
        return;
    }

    const auto profiles =
        solve_profiles_stoppable(solver, material, profile_request(grid, radii, false, o.solver, o.sampling, overrides), "export profile");
    if (profiles.partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": nothing written (the fit needs every channel's profile)\n";
        std::exit(InterruptGuard::exit_code());
    }
    ProfileShapeCheck shape;
    {
        const InterruptGuard interrupt;
        shape = stated_profile_shape(solver, material, grid, solver_switches(o.solver), &InterruptGuard::cancel_flag());
    }
    if (shape.stopped) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": nothing written (stopped in the profiles' shape check)\n";
        std::exit(InterruptGuard::exit_code());
    }
    print_profile_summary(profiles, shape);
    auto exported = fit_profile_export(profiles, bands, fit_request);
    if (profile_shape_checked(solver, material)) exported.shape = shape;
    const auto document = profile_export_json(exported);
    if (write_export(o, document, profile_export_table_csv(exported))) return;
    const auto& fit = exported.fit;
    std::cout << profile_export_header(exported);
    std::cout << fmt::format("{:>14}", "variance mm^2");
    for (const auto& n : exported.names) std::cout << fmt::format("{:>12}", n);
    std::cout << '\n';
    for (std::size_t i = 0; i < fit.variances_mm2.size(); ++i) {
        std::cout << fmt::format("{:>14.5g}", fit.variances_mm2[i]);
        for (const auto& w : fit.weights) std::cout << fmt::format("{:>12.5g}", w[i]);
        std::cout << '\n';
    }
    for (std::size_t c = 0; c < exported.names.size(); ++c) {
        const double total = exported.total_reflectance[c];
        std::cout << fmt::format("{}: profile error (relative L2, r dr) {:.3g} %; total R fit {:.5f} vs model {:.5f} ({:+.3g} %)\n", exported.names[c],
                                 100.0 * fit.relative_l2_error[c], fit.fitted_total[c], total,
                                 total != 0.0 ? 100.0 * (fit.fitted_total[c] - total) / total : 0.0);
    }
}

}  // namespace

void add_export_profile_command(CLI::App& exporter) {
    auto o = std::make_shared<ProfileExportOptions>();
    auto* cmd = exporter.add_subcommand("profile", "R(r) fitted as a sum of Gaussians with shared variances (d'Eon et al. 2007), JSON and a table");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    add_solver_options(*cmd, o->solver, profile_solver_default);
    cmd->add_option("--per", o->channels, "rgb: one fit per colour band (the profile's colour in linear --space); wavelength: one per --wavelengths")
        ->capture_default_str();
    cmd->add_option("--wavelengths", o->wavelengths, "With --per wavelength: wavelengths (nm), default 450,550,650");
    cmd->add_option("--space", o->space, "With --per rgb: the linear RGB space of the bands (an OCIO colour space)")->capture_default_str();
    cmd->add_option("--illuminant", o->illuminant, "With --per rgb: D65, D50, A or E")->capture_default_str();
    cmd->add_option("--observer", o->observer, "With --per rgb: 2 or 10")->capture_default_str();
    cmd->add_option("--gaussians", o->gaussians, "Number of Gaussians, [1, 12]")->capture_default_str();
    cmd->add_option("--radii", o->radii, "FIRST:LAST:STEP in mm: where R(r) is fitted")->capture_default_str();
    add_profile_sampling_options(*cmd, o->sampling);
    cmd->add_option("--vary", o->vary,
                    "FIELD=FIRST:LAST:STEPS[:log], at most twice (a grid): every member's fit, one set of variances for all (the exact "
                    "transport: one walk per wavelength for the whole grid)");
    cmd->add_option("-o,--output", o->output, "JSON file of the fit (default: the JSON on standard output)");
    cmd->add_option("--table", o->table, "CSV table of variances and weights");
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->add_flag("--json", o->json, "Print the fit as JSON (what -o writes) instead of the table");
    cmd->callback([o, cmd] {
        note_given_profile_sampling(*cmd, o->sampling);
        run_export_profile(*o);
    });
}

}  // namespace skinspec::cli
