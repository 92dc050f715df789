// Benchmark of absorption replay (docs/PERFORMANCE.md, "Absorption replay"), side by side in one run on all
// cores, biospec-moderately, 400-700 nm / 10 nm, stderr <= 0.002 at every wavelength of every level:
//  1. one level (the preset, v_m 0.052) and the lightest level of the sweep (v_m 0.005) on their own;
//  2. a 100-level melanosome sweep 0.005-0.25 (log) replayed from one set of traced paths;
//  3. the same sweep level by level (the way without replay): 10 of its levels timed, times 10;
//  4. the default swatch chart (40 patches, Delta E 0.3), replayed and patch by patch;
//  5. the volumetric walk (white Monte Carlo) on the slab n 1.4, mu_s 100/cm, g 0.9, 0.1 cm: 20 absorption levels
//     mu_a 0.1-10/cm (log) replayed from one trace against 20 white runs, 200,000 photons each;
// and the per-set cost of a replay in ns per ray per layer (one-thread CPU time).
// Usage: skinspec_bench_replay
#include <chrono>
#include <functional>
#include <iostream>

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include "bench/bench_timing.hpp"
#include "appearance/swatch_chart.hpp"
#include "materials/parameter_sweep.hpp"
#include "solvers/spectral_solver.hpp"
#include "transport/rte/rte_model.hpp"

using namespace skinspec;
using skinspec::bench::seconds_of;

namespace {


std::uint64_t total_rays(const SpectralResult& r) {
    std::uint64_t rays = 0;
    for (const auto& w : r.wavelengths) rays += w.rays;
    return rays;
}

double worst_stderr(const std::vector<SpectralResult>& results) {
    double worst = 0.0;
    for (const auto& r : results) {
        for (const auto& w : r.wavelengths) worst = std::max(worst, w.reflectance.stderr);
    }
    return worst;
}

}  // namespace

int main() {
    const auto& walk = find_solver("biospec");
    SolverRequest request;
    request.spectral.wavelengths = WavelengthGrid::range(400.0, 700.0, 10.0);
    request.spectral.stderr_target = 0.002;
    request.spectral.max_rays_per_wavelength = 10'000'000;
    const auto sweep = parse_sweep("epidermis.melanosome_fraction=0.005:0.25:100:log");
    const auto preset = load_material("biospec-moderately");
    const auto base = std::make_shared<const Material>(preset);
    std::vector<SweepMember> members;
    const auto fields = swept_fields({sweep.axis()});
    for (const auto& values : sweep_grid({sweep.axis()})) members.push_back({base, {fields, values}, nullptr, {}});
    solve_spectrum(walk, preset, request);  // warm-up: tables loaded

    SpectralResult one, lightest;
    const double t_one = seconds_of([&] { one = solve_spectrum(walk, preset, request); });
    const double t_light = seconds_of([&] { lightest = solve_spectrum(walk, members.front().material(), request); });
    std::vector<SpectralResult> replayed;
    const double t_sweep = seconds_of([&] { replayed = solve_sweep(walk, members, request); });
    double t_direct10 = 0.0;
    std::vector<SpectralResult> direct;
    for (std::size_t i = 0; i < members.size(); i += 10) {
        t_direct10 += seconds_of([&] { direct.push_back(solve_spectrum(walk, members[i].material(), request)); });
    }
    const double t_direct = 10.0 * t_direct10;
    const auto threads = tbb::this_task_arena::max_concurrency();
    std::cout << fmt::format("absorption replay, biospec-moderately, 400-700 nm / 10 nm, stderr <= 0.002, {} thread(s)\n", threads);
    std::cout << fmt::format("  one level (v_m 0.052):             {:8.3f} s, {:>10} rays\n", t_one, total_rays(one));
    std::cout << fmt::format("  lightest level alone (v_m 0.005):  {:8.3f} s, {:>10} rays\n", t_light, total_rays(lightest));
    std::cout << fmt::format("  100-level sweep, replayed:         {:8.3f} s, {:>10} rays, worst stderr {:.4f}: {:.2f}x one level, "
                             "{:.2f}x the lightest\n",
                             t_sweep, total_rays(replayed.front()), worst_stderr(replayed), t_sweep / t_one, t_sweep / t_light);
    std::cout << fmt::format("  100-level sweep, level by level:   {:8.3f} s (10 levels timed x 10), worst stderr {:.4f}: replay {:.1f}x "
                             "faster\n", t_direct, worst_stderr(direct), t_direct / t_sweep);

    // Per-set cost: one thread, fixed rays, 100 sets against 1 set at the lightest level.
    {
        tbb::task_arena single(1);
        SolverRequest fixed = request;
        fixed.fixed_rays_per_wavelength = 20'000;
        double t1 = 0.0, t100 = 0.0;
        single.execute([&] {
            t1 = seconds_of([&] { solve_spectrum(walk, members.front().material(), fixed); });
            t100 = seconds_of([&] { solve_sweep(walk, members, fixed); });
        });
        const double ray_layers = 20'000.0 * 31.0 * 4.0;
        std::cout << fmt::format("  per-set cost (1 thread, 20,000 rays x 31 wavelengths): {:.1f} ns per ray per layer per extra set "
                                 "(1 set {:.3f} s, 100 sets {:.3f} s)\n",
                                 1e9 * (t100 - t1) / (ray_layers * 99.0), t1, t100);
    }

    SwatchRequest chart;
    chart.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.01:0.42:8:log"), parse_sweep("dermis.blood_fraction=0.002:0.05:5")};
    SwatchChart with, without;
    const double t_chart = seconds_of([&] { with = compute_swatch(chart); });
    chart.patches_per_sweep = 1;
    const double t_chart_direct = seconds_of([&] { without = compute_swatch(chart); });
    double worst_with = 0.0, worst_without = 0.0;
    for (const auto& p : with.patches) worst_with = std::max(worst_with, p.uncertainty.delta_e2000);
    for (const auto& p : without.patches) worst_without = std::max(worst_without, p.uncertainty.delta_e2000);
    std::cout << fmt::format("  default swatch (40 patches, Delta E 0.3): replayed {:.3f} s (worst dE {:.3f}), patch by patch {:.3f} s "
                             "(worst dE {:.3f}): {:.1f}x faster\n",
                             t_chart, worst_with, t_chart_direct, worst_without, t_chart_direct / t_chart);

    RteRequest slab;
    slab.stack.layers.push_back({1.4, 1.0, 100.0, 0.1, PhaseFunction::henyey_greenstein(0.9)});
    slab.photons = 200'000;
    std::vector<std::vector<double>> levels;
    for (const double mu : parse_sweep("mu_a=0.1:10:20:log").values()) levels.push_back({mu});
    double t_white = 0.0;
    for (const auto& level : levels) {
        auto own = slab;
        own.white = true;
        own.stack.layers[0].mu_a_per_cm = level[0];
        t_white += seconds_of([&] { solve_rte(own); });
    }
    const double t_rte_replay = seconds_of([&] { solve_rte_sets(slab, levels); });
    std::cout << fmt::format("  volumetric walk, 20 absorption levels x 200,000 photons: replayed {:.3f} s, level by level {:.3f} s: "
                             "{:.1f}x faster\n", t_rte_replay, t_white, t_white / t_rte_replay);
    return 0;
}
