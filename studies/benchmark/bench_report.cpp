#include "studies/benchmark/bench_report.hpp"

#include "skinspec/version.hpp"

namespace skinspec {

bool is_walk(BenchSolver s) { return s == BenchSolver::biospec_walk || s == BenchSolver::volumetric_walk; }

std::vector<std::size_t> points_of(const BenchReport& report, std::size_t case_index) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < report.points.size(); ++i) {
        if (report.points[i].case_index == case_index) out.push_back(i);
    }
    return out;
}

CaseSummary summarise(const BenchReport& report, std::size_t case_index, double tolerance) {
    const auto indices = points_of(report, case_index);
    std::vector<double> seconds, errors;
    for (const auto i : indices) {
        seconds.push_back(report.points[i].seconds);
        errors.push_back(report.points[i].relative_error);
    }
    CaseSummary s;
    s.pareto = pareto_front(seconds, errors);
    if (const auto k = fastest_within(seconds, errors, tolerance)) s.fastest = indices[*k];
    for (const auto solver : {BenchSolver::biospec_walk, BenchSolver::volumetric_walk}) {
        std::vector<double> t, rays, e;
        for (const auto i : indices) {
            const auto& p = report.points[i];
            if (p.solver == solver && p.relative_error > 2.0 * report.cases[case_index].resolvable_error) {
                t.push_back(p.seconds);
                rays.push_back(static_cast<double>(p.rays));
                e.push_back(p.relative_error);
            }
        }
        if (!t.empty()) s.slopes.push_back({solver, fit_power_law(t, e), fit_power_law(rays, e)});
    }
    return s;
}

nlohmann::ordered_json bench_report_json(const BenchReport& report, const BenchReportSettings& o) {
    using Json = nlohmann::ordered_json;
    Json cases = Json::array();
    for (std::size_t c = 0; c < report.cases.size(); ++c) {
        const auto& k = report.cases[c];
        const auto summary = summarise(report, c, o.tolerance_percent / 100.0);
        Json points = Json::array();
        const auto indices = points_of(report, c);
        for (std::size_t j = 0; j < indices.size(); ++j) {
            const auto& p = report.points[indices[j]];
            points.push_back({{"solver", to_string(p.solver)}, {"rays", p.rays}, {"runs", p.repetitions}, {"seconds", p.seconds},
                              {"value", p.value.value}, {"value_stderr", p.value.stderr}, {"relative_error", p.relative_error},
                              {"pareto", static_cast<bool>(summary.pareto[j])}, {"note", p.note}});
        }
        Json slopes = Json::object();
        for (const auto& w : summary.slopes) {
            if (w.against_time && w.against_rays) {
                slopes[std::string(to_string(w.solver))] = {{"slope_against_time", w.against_time->slope}, {"slope_against_time_stderr", w.against_time->slope_stderr},
                                                            {"slope_against_rays", w.against_rays->slope}, {"slope_against_rays_stderr", w.against_rays->slope_stderr},
                                                            {"points", w.against_time->points}, {"seconds_for_tolerance", w.against_time->x_at(o.tolerance_percent / 100.0)}};
            }
        }
        cases.push_back({{"name", k.name}, {"quantity", k.quantity}, {"reference", k.reference.value}, {"reference_stderr", k.reference.stderr},
                         {"reference_source", k.reference_source}, {"resolvable_error", k.resolvable_error}, {"points", points}, {"walk_slopes", slopes},
                         {"fastest_within_tolerance", summary.fastest ? Json(std::string(to_string(report.points[*summary.fastest].solver))) : Json(nullptr)}});
    }
    Json pairs = Json::array();
    for (const auto& p : report.pair_sweep) pairs.push_back({{"tolerance", p.tolerance}, {"pairs", p.pairs}, {"seconds", p.seconds}, {"max_relative_error", p.max_relative_error}});
    Json scaling = Json::array();
    for (const auto& s : report.scaling) {
        scaling.push_back({{"solver", to_string(s.solver)}, {"workload", s.workload}, {"rays", s.rays}, {"seconds_one_thread", s.seconds_one_thread},
                           {"seconds_two_threads", s.seconds_two_threads}, {"speedup", s.seconds_one_thread / s.seconds_two_threads}});
    }
    Json colours = Json::array();
    for (const auto& c : report.colours) {
        colours.push_back({{"material", c.material}, {"seconds", c.seconds}, {"rays", c.rays}, {"delta_e_uncertainty", c.delta_e_uncertainty}, {"converged", c.converged}});
    }
    Json skin = Json::array();
    for (const auto& r : report.skin_modes) {
        skin.push_back({{"material", r.material}, {"solver", r.solver}, {"reference", r.reference}, {"seconds_one_thread", r.seconds_one_thread},
                        {"rays", r.rays}, {"uncertainty", r.uncertainty}, {"max_abs_error", r.max_abs_error},
                        {"min_relative_diffuse_error", r.min_relative_diffuse_error}, {"max_relative_diffuse_error", r.max_relative_diffuse_error},
                        {"delta_e_ab", r.delta_e_ab}, {"delta_e2000", r.delta_e2000},
                        {"stated_delta_e2000", r.stated_delta_e2000 ? Json(*r.stated_delta_e2000) : Json(nullptr)}});
    }
    Json agreement = Json::array();
    for (const auto& a : report.walk_agreement) {
        agreement.push_back({{"material", a.material}, {"wavelength_nm", a.wavelength_nm}, {"photons", a.photons}, {"walk", a.walk.value},
                             {"walk_stderr", a.walk.stderr}, {"adding_doubling", a.adding_doubling},
                             {"adding_doubling_accuracy", a.adding_doubling_accuracy}, {"sigma", (a.walk.value - a.adding_doubling) / a.walk.stderr},
                             {"fine_channels", a.fine_channels}, {"adding_doubling_fine", a.adding_doubling_fine},
                             {"sigma_fine", (a.walk.value - a.adding_doubling_fine) / a.walk.stderr}, {"seconds", a.seconds}});
    }
    Json profiles = Json::array();
    for (const auto& a : report.profile_agreement) {
        profiles.push_back({{"material", a.material}, {"wavelength_nm", a.wavelength_nm}, {"solver", a.solver}, {"photons", a.photons},
                            {"radii_compared", a.radii}, {"share_within_15_percent", a.share_within_15_percent},
                            {"worst_relative_error", a.worst_relative_error}, {"relative_error_at_0_1_mm", a.relative_error_at_0_1_mm},
                            {"median_relative_error_1_to_5_mm", a.median_relative_error_1_to_5_mm}, {"walk_seconds", a.walk_seconds}});
    }
    Json lit = Json::array();
    for (const auto& l : report.lit_swatches) {
        lit.push_back({{"material", l.material}, {"exact_seconds", l.exact_seconds}, {"matched_multipole_seconds", l.diffusion_seconds},
                       {"ratio", l.exact_seconds / l.diffusion_seconds}, {"photons", l.photons}, {"within_radius_stderr", l.within_radius_stderr},
                       {"converged", l.converged}});
    }
    Json grids = Json::array();
    for (const auto& g : report.profile_grids) {
        grids.push_back({{"material", g.material}, {"members", g.members}, {"one_member_seconds", g.one_member_seconds}, {"grid_seconds", g.grid_seconds},
                         {"ratio", g.grid_seconds / g.one_member_seconds}, {"photons", g.photons}, {"within_radius_stderr", g.within_radius_stderr},
                         {"worst_profile_relative_l2_error", g.worst_profile_error}});
    }
    return {{"skinspec_version", version}, {"quick", o.quick}, {"seed", o.seed}, {"tolerance_percent", o.tolerance_percent}, {"partial", report.partial},
            {"cases", cases}, {"multipole_pair_sweep", pairs}, {"thread_scaling", scaling}, {"time_per_colour", colours},
            {"skin_in_every_mode", skin}, {"walk_against_adding_doubling", agreement}, {"profiles_against_the_walk", profiles}, {"lit_swatches", lit},
            {"profile_grids", grids}};
}

}  // namespace skinspec
