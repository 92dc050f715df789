#include "cli/profile_command.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "appearance/profile_shape_report.hpp"
#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "cli/profile_shape_output.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "cli/spectral_output.hpp"
#include "formats/profile_inputs.hpp"
#include "materials/material_file.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/line_plot.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

struct ProfileOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    SolverOptions solver;
    std::string wavelengths = "450,550,650";
    std::string radii = "0:10:0.01";
    std::string output;
    std::string plot;
    bool overwrite = false;
    ProfileSampling sampling;
};

std::string column_tag(const ChannelProfile& c) {
    return c.wavelength_nm > 0.0 ? fmt::format("{:g}nm", c.wavelength_nm) : "band" + c.label;
}

std::string to_csv(const SpectralProfiles& p, const ProfileShapeCheck& shape) {
    std::string out = fmt::format("# skinspec {} radial profiles: material {}, model {}, partial {}\n", version, p.material, p.model, p.partial);
    out += "# units: r_mm [mm]; R_*, T_* [1/mm^2 per unit incident power, entry Fresnel transmittance included]\n";
    for (const auto& c : p.channels) {
        out += fmt::format("# {}: diffuse R total {:.6g}, T total {:.6g}, specular {:.6g}\n", c.label, c.total_reflectance,
                           c.total_transmittance, c.specular_reflectance);
    }
    // For readers that want R per unit power entering (fit-profile, formats/profile_inputs.hpp): one figure per column.
    out += std::string(radial_entry_transmittance_comment);
    for (std::size_t k = 0; k < p.channels.size(); ++k) {
        const auto& c = p.channels[k];
        out += fmt::format("{}R_{}_per_mm2={:.9g}", k == 0 ? " " : ", ", column_tag(c), 1.0 - c.specular_reflectance);
    }
    out += '\n';
    // The diffusion sums' own figures, only where a diffusion model made the profiles (the walk has neither).
    if (p.max_pairs > 0 || p.frequencies > 0) {
        out += fmt::format("# dipole pairs (largest): {}, inverse-transform samples: {}, converged: {}\n", p.max_pairs, p.frequencies,
                           p.converged ? "yes" : "NO");
    } else if (!p.converged) {
        out += "# converged: NO\n";
    }
    for (const auto& w : summarise_warnings(p.warnings)) out += "# warning: " + w + "\n";
    if (const auto precision = profile_precision_line(p); !precision.empty()) out += "# " + precision + "\n";
    for (const auto& line : profile_shape_lines(shape)) out += "# " + line + "\n";
    // Monte Carlo profiles add a standard-error column after each value column.
    const bool errors = !p.channels.empty() && !p.channels.front().reflectance_stderr_per_mm2.empty();
    out += "r_mm";
    for (const auto& c : p.channels) out += ",R_" + column_tag(c) + "_per_mm2" + (errors ? ",R_" + column_tag(c) + "_stderr_per_mm2" : "");
    for (const auto& c : p.channels) out += ",T_" + column_tag(c) + "_per_mm2" + (errors ? ",T_" + column_tag(c) + "_stderr_per_mm2" : "");
    out += '\n';
    const auto value = [&](const std::vector<double>& v, const std::vector<double>& e, std::size_t i) {
        const double x = i < v.size() ? v[i] : 0.0;
        return errors ? fmt::format(",{:.9g},{:.3g}", x, i < e.size() ? e[i] : 0.0) : fmt::format(",{:.9g}", x);
    };
    for (std::size_t i = 0; i < p.radii_mm.size(); ++i) {
        out += fmt::format("{:g}", p.radii_mm[i]);
        for (const auto& c : p.channels) out += value(c.reflectance_per_mm2, c.reflectance_stderr_per_mm2, i);
        for (const auto& c : p.channels) out += value(c.transmittance_per_mm2, c.transmittance_stderr_per_mm2, i);
        out += '\n';
    }
    return out;
}

void write_profile_plot(const std::string& file, const SpectralProfiles& p) {
    std::vector<PlotCurve> curves;
    bool any_t = false;
    for (std::size_t k = 0; k < p.channels.size(); ++k) {
        const auto& c = p.channels[k];
        const auto style = distinct_series_style(k);
        curves.push_back({"R " + c.label, p.radii_mm, c.reflectance_per_mm2, c.reflectance_stderr_per_mm2, style.colour, false, style.marker});
        bool has_t = false;
        for (const double v : c.transmittance_per_mm2) has_t = has_t || v > 0.0;
        if (has_t) {
            curves.push_back({"T " + c.label, p.radii_mm, c.transmittance_per_mm2, c.transmittance_stderr_per_mm2, style.colour, true, style.marker});
            any_t = true;
        }
    }
    write_line_plot(file, fmt::format("{} ({}): radial reflectance profiles", p.material, p.model), "Radius r (mm)",
                    any_t ? "R(r), T(r) (1/mm^2)" : "R(r) (1/mm^2)", curves, {.log_y = true});
}

void run_profile(const ProfileOptions& o) {
    if (!o.preset.empty() && !o.material_file.empty()) throw InputError("--preset and --material: give one material, not both");
    const auto radii = parse_radii_mm(o.radii, "--radii");
    const auto grid = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    if (!o.output.empty()) check_output_path(o.output, o.overwrite, {".csv"});
    if (!o.plot.empty()) check_output_path(o.plot, o.overwrite, {".png", ".svg"});
    std::vector<MaterialOverride> overrides;
    for (const auto& t : o.overrides) overrides.push_back(parse_override(t));
    const auto material = load_material(o.material_file.empty() ? (o.preset.empty() ? "biospec-moderately" : o.preset) : o.material_file, overrides);
    const auto& solver = chosen_profile_solver(o.solver);
    const auto profiles = solve_profiles_stoppable(solver, material, profile_request(grid, radii, true, o.solver, o.sampling, overrides), "profile");
    ProfileShapeCheck shape;
    if (!profiles.partial) {
        const InterruptGuard interrupt;
        shape = stated_profile_shape(solver, material, grid, solver_switches(o.solver), &InterruptGuard::cancel_flag());
    }
    print_profile_summary(profiles, shape);
    const auto csv = to_csv(profiles, shape);
    if (o.output.empty()) {
        std::cout << csv;
    } else {
        write_text_file(o.output, csv, o.overwrite);
        std::cerr << "wrote " << o.output << '\n';
    }
    if (!o.plot.empty()) {
        write_profile_plot(o.plot, profiles);
        std::cerr << "wrote " << o.plot << '\n';
    }
    if (profiles.partial) {
        std::cerr << fmt::format("skinspec: {}: the {} of {} channels finished were written, marked partial\n", InterruptGuard::reason(),
                                 profiles.channels.size(), profile_channel_count(material, grid));
        std::exit(InterruptGuard::exit_code());
    }
    if (shape.stopped) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": the profiles were written; their shape check stopped (its finished wavelengths stated)\n";
        std::exit(InterruptGuard::exit_code());
    }
}

}  // namespace

void add_profile_command(CLI::App& app) {
    auto o = std::make_shared<ProfileOptions>();
    auto* cmd = app.add_subcommand("profile", "Radial diffuse reflectance R(r) and transmittance T(r) of a solver that computes them (CSV, plot)");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    add_solver_options(*cmd, o->solver, profile_solver_default);
    cmd->add_option("--wavelengths", o->wavelengths, "Wavelengths (nm) for layered materials; homogeneous ones use their bands")->capture_default_str();
    cmd->add_option("--radii", o->radii, "FIRST:LAST:STEP in mm")->capture_default_str();
    cmd->add_option("--output", o->output, "CSV file (default: standard output)");
    cmd->add_option("--plot", o->plot, "Log-scale plot, FILE.png or FILE.svg");
    add_profile_sampling_options(*cmd, o->sampling);
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->callback([o, cmd] {
        note_given_profile_sampling(*cmd, o->sampling);
        run_profile(*o);
    });
}

}  // namespace skinspec::cli
