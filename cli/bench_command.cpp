#include "cli/bench_command.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/common_options.hpp"
#include "cli/progress.hpp"
#include "cli/spectral_output.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/line_plot.hpp"
#include "spectral/text_fields.hpp"
#include "studies/benchmark/error_fits.hpp"
#include "studies/benchmark/bench_report.hpp"
#include "studies/benchmark/runtime_benchmark.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct BenchCommandOptions {
    bool quick = false;
    std::uint64_t seed = 1;
    double tolerance_percent = 1.0;
    std::string output, plot;
    bool json = false;
    bool overwrite = false;
};

std::string budget_text(const BenchPoint& p) {
    return p.rays > 0 ? fmt::format("{} rays x{}", p.rays, p.repetitions) : std::string("closed form");
}

void print_report(const BenchReport& report, const BenchCommandOptions& o) {
    const double tolerance = o.tolerance_percent / 100.0;
    std::cout << fmt::format("skinspec bench{}: run time against error, seed {} (reference runs: a different seed)\n",
                             o.quick ? " --quick" : "", o.seed);
    for (std::size_t c = 0; c < report.cases.size(); ++c) {
        const auto& k = report.cases[c];
        const auto summary = summarise(report, c, tolerance);
        std::cout << fmt::format("\n{}: {} reference {:.6f}{} [{}{}]\n", k.name, k.quantity, k.reference.value,
                                 k.reference.stderr > 0 ? fmt::format(" +- {:.6f}", k.reference.stderr) : std::string(), k.reference_source,
                                 k.reference_seconds > 0 ? fmt::format(", {:.1f} s", k.reference_seconds) : std::string());
        std::cout << fmt::format("  {:<10} {:>20} {:>12} {:>22} {:>10} {:>6}\n", "solver", "budget", "seconds", "value", "error %", "pareto");
        const auto indices = points_of(report, c);
        for (std::size_t j = 0; j < indices.size(); ++j) {
            const auto& p = report.points[indices[j]];
            std::cout << fmt::format("  {:<10} {:>20} {:>12.4g} {:>22} {:>10.3f} {:>6}{}\n", to_string(p.solver), budget_text(p), p.seconds,
                                     p.value.stderr > 0 ? fmt::format("{:.5f} +- {:.5f}", p.value.value, p.value.stderr) : fmt::format("{:.5f}", p.value.value),
                                     100.0 * p.relative_error, summary.pareto[j] ? "*" : "", p.note.empty() ? std::string() : "  (" + p.note + ")");
        }
        for (const auto& w : summary.slopes) {
            if (w.against_time && w.against_rays) {
                std::cout << fmt::format("  {} walk: error ~ time^({:.2f} +- {:.2f}), ~ rays^({:.2f} +- {:.2f}) over {} budgets (Monte Carlo: -0.5); "
                                         "{:g} % error in ~{:.3g} s (fitted)\n",
                                         to_string(w.solver), w.against_time->slope, w.against_time->slope_stderr, w.against_rays->slope,
                                         w.against_rays->slope_stderr, w.against_time->points, o.tolerance_percent, w.against_time->x_at(tolerance));
            }
        }
        if (summary.fastest) {
            const auto& p = report.points[*summary.fastest];
            std::cout << fmt::format("  fastest to {:g} % error: {} ({}, {:.3g} s)\n", o.tolerance_percent, to_string(p.solver), budget_text(p), p.seconds);
        } else {
            std::cout << fmt::format("  no solver reached {:g} % error within the budgets\n", o.tolerance_percent);
        }
        std::cout << fmt::format("  errors below {:.2g} % are not resolved by the reference\n", 100.0 * k.resolvable_error);
    }
    if (!report.pair_sweep.empty()) {
        std::cout << fmt::format("\nMultipole profile ({} radii, first slab) against the series summed to 1e-14:\n", report.pair_sweep_radii);
        std::cout << fmt::format("  {:>10} {:>8} {:>12} {:>16}\n", "tolerance", "pairs", "seconds", "max rel. error");
        for (const auto& p : report.pair_sweep) std::cout << fmt::format("  {:>10.0e} {:>8} {:>12.4g} {:>16.3g}\n", p.tolerance, p.pairs, p.seconds, p.max_relative_error);
    }
    if (!report.scaling.empty()) {
        std::cout << "\nThread scaling (rays per second per core):\n";
        for (const auto& s : report.scaling) {
            std::cout << fmt::format("  {:<8} {:<34} {:>9} rays: 1 thread {:.3g}/s, 2 threads {:.3g}/s per core, speed-up {:.2f}x\n", to_string(s.solver),
                                     s.workload, s.rays, s.rays / s.seconds_one_thread, s.rays / s.seconds_two_threads / 2.0,
                                     s.seconds_one_thread / s.seconds_two_threads);
        }
    }
    if (!report.colours.empty()) {
        std::cout << "\nTime per colour (one swatch patch, CIEDE2000 uncertainty <= 0.3, 2 threads):\n";
        for (const auto& c : report.colours) {
            std::cout << fmt::format("  {:<20} {:.3f} s, {} rays, Delta E uncertainty {:.3f}{}\n", c.material, c.seconds, c.rays, c.delta_e_uncertainty,
                                     c.converged ? "" : " (budget spent before the target)");
        }
    }
    if (!report.skin_modes.empty()) {
        std::cout << "\nOne skin in every mode: 400-700 nm / 10 nm (SCI), one thread, each mode against the exact solution of the description it "
                     "solves (biospec-adding-doubling: the BioSpec per-crossing description; adding-doubling: mu_a, mu_s, phase):\n";
        std::cout << fmt::format("  {:<20} {:<32} {:<25} {:>9} {:>10} {:>11} {:>10} {:>19} {:>9} {:>9} {:>10} {:>16}\n", "preset", "solver", "against", "seconds",
                                 "rays", "uncertainty", "max |dR|", "Rd error %", "dE*ab", "dE2000", "stated dE", "s at ref accuracy");
        std::map<std::pair<std::string, std::string>, double> accuracy;  // (preset, exact solver) -> its stated accuracy
        for (const auto& r : report.skin_modes) {
            if (r.rays == 0) accuracy[{r.material, r.solver}] = r.uncertainty;
            // A walk's time to reach its reference's stated accuracy: standard errors fall as rays^-1/2.
            const auto it = accuracy.find({r.material, r.reference});
            const bool walk = r.rays > 0 && r.uncertainty > 0.0 && it != accuracy.end() && it->second > 0.0;
            const std::string extrapolated = walk ? fmt::format("{:.3g}", r.seconds_one_thread * std::pow(r.uncertainty / it->second, 2.0)) : "";
            const std::string against = r.reference == r.solver ? "(itself: the reference)"
                                        : r.solver == own_description_row ? r.reference + " *"
                                                                        : r.reference;
            std::cout << fmt::format("  {:<20} {:<32} {:<25} {:>9.4f} {:>10} {:>11.2g} {:>10.4f} {:>8.1f} .. {:>6.1f} {:>9.2f} {:>9.2f} {:>10} {:>16}\n",
                                     r.material, r.solver, against, r.seconds_one_thread, r.rays, r.uncertainty, r.max_abs_error,
                                     100.0 * r.min_relative_diffuse_error, 100.0 * r.max_relative_diffuse_error, r.delta_e_ab, r.delta_e2000,
                                     r.stated_delta_e2000 ? fmt::format("{:.2f}", *r.stated_delta_e2000) : std::string(), extrapolated);
        }
        std::cout << "  (uncertainty: a walk's largest standard error of R; adding-doubling's stated accuracy, twice the change with every segment's channels doubled;\n"
                     "   adding-doubling: the volumetric description derived from the BioSpec one, as the presets set it;\n"
                     "   *: the preset's own volumetric description (model.volumetric_matched_to_biospec=false) against the BioSpec one, the gap the derivation closes)\n";
    }
    if (!report.lit_swatches.empty()) {
        std::cout << "\nLit swatch (spot 2 mm, 20 mm field, 256 x 256 px, 400-700 nm / 10 nm, all threads), side by side:\n";
        for (const auto& l : report.lit_swatches) {
            std::cout << fmt::format("  {:<20} exact (rte, default precision) {:.2f} s, matched-multipole {:.2f} s: ratio {:.2f}x; {} photons, "
                                     "R within a radius to +- {:.4f}{}\n",
                                     l.material, l.exact_seconds, l.diffusion_seconds, l.exact_seconds / l.diffusion_seconds, l.photons,
                                     l.within_radius_stderr, l.converged ? "" : " (budget spent before the target)");
        }
    }
    if (!report.profile_grids.empty()) {
        std::cout << "\nExport profile of a melanosome x blood grid against one member (exact transport, default precision, RGB fit, all threads), side by side:\n";
        for (const auto& g : report.profile_grids) {
            std::cout << fmt::format("  {}: {} members {:.2f} s, one member {:.2f} s: ratio {:.2f}x; {} photons per wavelength for the whole grid, "
                                     "R within a radius to +- {:.4f}, worst member's fit error {:.3g} %\n",
                                     g.material, g.members, g.grid_seconds, g.one_member_seconds, g.grid_seconds / g.one_member_seconds, g.photons,
                                     g.within_radius_stderr, 100.0 * g.worst_profile_error);
        }
    }
    if (!report.walk_agreement.empty()) {
        std::cout << "\nVolumetric walk against adding-doubling (R, SCI):\n";
        for (const auto& a : report.walk_agreement) {
            std::cout << fmt::format("  {:<20} {:.0f} nm, {} photons in {:.1f} s: walk {:.6f} +- {:.6f}; adding-doubling {:.6f} (accuracy {:.1e}), "
                                     "walk {:+.2f} sigma; with {} channels {:.6f}, walk {:+.2f} sigma\n",
                                     a.material, a.wavelength_nm, a.photons, a.seconds, a.walk.value, a.walk.stderr, a.adding_doubling,
                                     a.adding_doubling_accuracy, (a.walk.value - a.adding_doubling) / a.walk.stderr, a.fine_channels,
                                     a.adding_doubling_fine, (a.walk.value - a.adding_doubling_fine) / a.walk.stderr);
        }
    }
    if (!report.profile_agreement.empty()) {
        std::cout << "\nR(r) against the volumetric walk (0.05-5 mm where the walk's standard error is below 5 %; relative errors):\n";
        std::cout << fmt::format("  {:<20} {:>6} {:<18} {:>10} {:>7} {:>12} {:>10} {:>10} {:>16}\n", "preset", "nm", "solver", "photons", "radii",
                                 "within 15 %", "worst", "at 0.1 mm", "median 1-5 mm");
        for (const auto& a : report.profile_agreement) {
            std::cout << fmt::format("  {:<20} {:>6g} {:<18} {:>10} {:>7} {:>11.0f}% {:>+9.0f}% {:>+9.0f}% {:>+15.0f}%\n", a.material, a.wavelength_nm, a.solver,
                                     a.photons, a.radii, 100.0 * a.share_within_15_percent, 100.0 * a.worst_relative_error,
                                     100.0 * a.relative_error_at_0_1_mm, 100.0 * a.median_relative_error_1_to_5_mm);
        }
        std::cout << "  (the walk solves the volumetric description, on the presets the one derived from the BioSpec model, by whose reduced scattering "
                     "matched-multipole spreads (its totals are the BioSpec model's); the multipole and dipole spread by the layers' own reduced scattering)\n";
    }
    if (report.partial) std::cout << "\nstopped early: the figures above are what finished\n";
}

std::string to_csv(const BenchReport& report) {
    std::string csv = fmt::format("# skinspec {} bench: one row per solver and budget; seconds per run (wall, 2 threads); error relative, RMS over the runs\n"
                                  "{}case,quantity,reference,reference_stderr,solver,rays,runs,seconds,value,value_stderr,relative_error\n",
                                  version, report.partial ? "# partial: true (stopped; the rows below finished, the others were not run)\n" : "");
    for (const auto& p : report.points) {
        const auto& c = report.cases[p.case_index];
        csv += fmt::format("\"{}\",{},{:.9g},{:.3g},{},{},{},{:.6g},{:.9g},{:.3g},{:.6g}\n", c.name, c.quantity, c.reference.value, c.reference.stderr,
                           to_string(p.solver), p.rays, p.repetitions, p.seconds, p.value.value, p.value.stderr, p.relative_error);
    }
    return csv;
}

// Error against time, log-log, a panel per case: a line per walk; a diffusion point as a dashed level from its time
// on. An error the reference cannot resolve is drawn on the reference's resolution (grey), as the upper bound it is.
void write_plot(const std::string& file, const BenchReport& report) {
    double longest = 0.0;
    for (const auto& p : report.points) longest = std::max(longest, p.seconds);
    std::vector<PlotPanel> panels;
    for (std::size_t c = 0; c < report.cases.size(); ++c) {
        const auto& k = report.cases[c];
        PlotPanel panel{fmt::format("Relative error of {} (%)", k.quantity), {}, {.log_x = true, .log_y = true}, k.name};
        for (const auto solver : {BenchSolver::biospec_walk, BenchSolver::volumetric_walk, BenchSolver::multipole, BenchSolver::dipole, BenchSolver::adding_doubling}) {
            const auto style = distinct_series_style(static_cast<std::size_t>(solver));
            PlotCurve curve{std::string(to_string(solver)), {}, {}, {}, style.colour, !is_walk(solver), style.marker};
            for (const auto i : points_of(report, c)) {
                const auto& p = report.points[i];
                if (p.solver != solver) continue;
                const double percent = 100.0 * std::max(p.relative_error, k.resolvable_error);
                curve.x.push_back(p.seconds);
                curve.value.push_back(percent);
                if (!is_walk(solver)) {
                    curve.x.push_back(longest);
                    curve.value.push_back(percent);
                }
            }
            if (!curve.x.empty()) panel.curves.push_back(std::move(curve));
        }
        if (k.resolvable_error > 0.0 && !panel.curves.empty()) {
            double first = longest;
            for (const auto& curve : panel.curves) first = std::min(first, curve.x.front());
            panel.curves.push_back({"reference's resolution (errors below it drawn on it)", {first, longest},
                                    {100.0 * k.resolvable_error, 100.0 * k.resolvable_error}, {}, {0.55, 0.55, 0.55}, true, 0});
        }
        if (!panel.curves.empty()) panels.push_back(std::move(panel));
    }
    write_figure(file, "Error against run time", "Run time (s); walks solid, diffusion and adding-doubling dashed", panels);
}

void run_bench(const BenchCommandOptions& o) {
    if (!(o.tolerance_percent > 0.0 && o.tolerance_percent < 100.0)) {
        throw InputError("--tolerance = " + format_number(o.tolerance_percent) + " % is outside (0, 100)");
    }
    if (!o.output.empty()) check_output_path(o.output, o.overwrite, {".csv", ".json"});
    if (!o.plot.empty()) check_output_path(o.plot, o.overwrite, {".png", ".svg"});
    const InterruptGuard interrupt;
    BenchOptions options;
    options.quick = o.quick;
    options.seed = o.seed;
    options.cancel = &InterruptGuard::cancel_flag();
    options.on_stage = [](const std::string& stage) { std::cerr << "bench: " << stage << '\n'; };
    const auto report = run_benchmark(options);
    if (o.json) std::cout << bench_report_json(report, {o.quick, o.seed, o.tolerance_percent}).dump(2) << '\n';
    else print_report(report, o);
    if (!report.points.empty() && !o.output.empty()) {
        write_text_file(o.output, o.output.ends_with(".json") ? bench_report_json(report, {o.quick, o.seed, o.tolerance_percent}).dump(2) + "\n" : to_csv(report), o.overwrite);
        std::cerr << "wrote " << o.output << '\n';
    }
    if (!report.points.empty() && !o.plot.empty()) {
        write_plot(o.plot, report);
        std::cerr << "wrote " << o.plot << '\n';
    }
    // Stopped like every other command: 128 + the signal, after writing what finished (marked partial).
    if (InterruptGuard::interrupted()) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": the figures that finished were reported, marked partial\n";
        std::exit(InterruptGuard::exit_code());
    }
}

}  // namespace

void add_bench_command(CLI::App& app) {
    auto o = std::make_shared<BenchCommandOptions>();
    auto* cmd = app.add_subcommand("bench", "Run time against error for every solver: slopes, Pareto front, thread scaling, time per colour");
    cmd->add_flag("--quick", o->quick, "The short form (under a minute): fewer budgets and seeds, shorter references");
    add_seed_option(*cmd, o->seed, "Seed of the swept runs (the references use a different one)");
    cmd->add_option("--tolerance", o->tolerance_percent, "Relative error (%) for 'which solver is fastest'")->capture_default_str();
    cmd->add_option("--output", o->output, "Write every point to FILE.csv, or the whole report to FILE.json");
    cmd->add_flag("--json", o->json, "Print the whole report as JSON on standard output (instead of the tables)");
    cmd->add_option("--plot", o->plot, "Log-log plot of error against time, FILE.png or FILE.svg");
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->callback([o] { run_bench(*o); });
}

}  // namespace skinspec::cli
