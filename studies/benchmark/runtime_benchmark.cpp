#include "studies/benchmark/runtime_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <span>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "solvers/spectral_solver.hpp"
#include "transport/diffusion/diffusion_model.hpp"
#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/multipole.hpp"
#include "transport/fresnel.hpp"
#include "formats/adding_doubling_reference.hpp"
#include "transport/rte/rte_model.hpp"
#include "appearance/lit_swatch.hpp"
#include "appearance/profile_export.hpp"
#include "materials/parameter_sweep.hpp"
#include "appearance/swatch_chart.hpp"
#include "spectral/ciede2000.hpp"
#include "spectral/colorimetry.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "materials/material_file.hpp"

namespace skinspec {

std::string_view to_string(BenchSolver solver) {
    switch (solver) {
        case BenchSolver::biospec_walk: return "biospec";
        case BenchSolver::volumetric_walk: return "rte";
        case BenchSolver::dipole: return "dipole";
        case BenchSolver::multipole: return "multipole";
        case BenchSolver::adding_doubling: return "adding-doubling";
    }
    return "?";
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Mean wall time of `call`, repeated until at least `min_seconds` have passed (at least once).
double mean_seconds_per_call(const std::function<void()>& call, double min_seconds) {
    int calls = 0;
    const auto start = Clock::now();
    do {
        call();
        ++calls;
    } while (seconds_since(start) < min_seconds);
    return seconds_since(start) / calls;
}

struct Stopped {};

struct Plan {
    std::vector<std::string> skin_presets;   // one skin in every mode
    bool skin_volumetric_walk;               // its 31-wavelength spectrum too (tens of seconds per preset)
    std::uint64_t agreement_photons;         // the volumetric walk against adding-doubling at 550 nm, and its R(r)
    bool quick_profiles;                     // R(r) at 550 nm only (else 450, 550, 650)
    std::vector<std::uint64_t> rays;
    int repetitions;
    std::uint64_t reference_rays;
    double min_timing_seconds;  // deterministic solvers are repeated for at least this long
    std::uint64_t scaling_rays;
    std::vector<std::string> colour_materials;
};

Plan plan_of(bool quick) {
    if (quick) return {{"biospec-moderately"}, false, 200'000, true, {1000, 4000, 16000, 64000, 256000}, 4, 4'000'000, 0.02, 400'000, {"biospec-moderately"}};
    const std::vector<std::string> presets{"biospec-lightly", "biospec-moderately", "biospec-heavily"};
    // One skin in every mode on every biospec preset (the darkest included: where the derived description is hardest).
    const std::vector<std::string> skin{"biospec-lightly", "biospec-moderately", "biospec-heavily", "biospec-very-heavily"};
    return {skin, true, 10'000'000, false, {1000, 3162, 10000, 31623, 100000, 316228, 1'000'000}, 6, 20'000'000, 0.1, 4'000'000, presets};
}

class Benchmark {
public:
    explicit Benchmark(const BenchOptions& options) : options_(options), plan_(plan_of(options.quick)) {}

    BenchReport& report() { return report_; }

    void stage(const std::string& text) const {
        if (options_.on_stage) options_.on_stage(text);
    }
    void check_cancel() const {
        if (options_.cancel && options_.cancel->load()) throw Stopped{};
    }

    std::size_t add_case(BenchCase c) {
        report_.cases.push_back(std::move(c));
        return report_.cases.size() - 1;
    }

    // A long run of a walk with the reference seed as the case's reference.
    std::size_t add_walk_reference_case(std::string name, std::string quantity, const std::function<Estimate(std::uint64_t, std::uint64_t)>& run,
                                        const std::string& solver_name) {
        stage(fmt::format("{}: reference ({} rays)", name, plan_.reference_rays));
        const auto start = Clock::now();
        const auto reference = run(plan_.reference_rays, options_.reference_seed);
        const double seconds = seconds_since(start);
        check_cancel();
        return add_case({std::move(name), std::move(quantity), reference, 2.0 * reference.stderr / reference.value,
                         fmt::format("{} walk, {} rays, seed {} (+- {:.2g} %)", solver_name, plan_.reference_rays, options_.reference_seed,
                                     100.0 * reference.stderr / reference.value),
                         seconds});
    }

    // The walk at every budget, `repetitions` seeds each.
    void sweep_walk(std::size_t case_index, BenchSolver solver, const std::function<Estimate(std::uint64_t, std::uint64_t)>& run) {
        const auto& c = report_.cases[case_index];
        stage(fmt::format("{}: {} walk, {} budgets x {} seeds", c.name, to_string(solver), plan_.rays.size(), plan_.repetitions));
        for (const auto rays : plan_.rays) {
            BenchPoint p{case_index, solver, rays, plan_.repetitions, 0.0, {}, 0.0, {}};
            double squares = 0.0, seconds = 0.0;
            for (int k = 0; k < plan_.repetitions; ++k) {
                const auto start = Clock::now();
                const auto e = run(rays, options_.seed + static_cast<std::uint64_t>(k));
                seconds += seconds_since(start);
                check_cancel();
                if (k == 0) p.value = e;
                const double error = (e.value - c.reference.value) / c.reference.value;
                squares += error * error;
            }
            p.seconds = seconds / plan_.repetitions;
            p.relative_error = std::sqrt(squares / plan_.repetitions);
            report_.points.push_back(p);
        }
    }

    // A deterministic solver: timed over repeated calls.
    void time_deterministic(std::size_t case_index, BenchSolver solver, const std::function<double()>& evaluate, std::string note = {}) {
        const auto& c = report_.cases[case_index];
        double value = evaluate();
        const double seconds = mean_seconds_per_call([&] { value = evaluate(); }, plan_.min_timing_seconds);
        BenchPoint p{case_index, solver, 0, 1, seconds, {value, 0.0},
                     std::abs(value - c.reference.value) / c.reference.value, std::move(note)};
        report_.points.push_back(p);
        check_cancel();
    }

    const BenchOptions& options() const { return options_; }
    const Plan& plan() const { return plan_; }

private:
    BenchOptions options_;
    Plan plan_;
    BenchReport report_;
};

std::string trust_note(const SpectralResult& result) {
    return result.warnings.empty() ? std::string() : fmt::format("{} trust warning(s): {}", result.warnings.size(), summarise_warnings(result.warnings).front());
}

// Prahl's slabs: Rd by the volumetric walk, the multipole (finite slab) and the dipole (semi-infinite).
void adding_doubling_cases(Benchmark& bench, const std::vector<AddingDoublingSlab>& slabs) {
    for (const std::size_t row : {0u, 3u, 5u}) {
        const auto& slab = slabs.at(row);
        const auto index = bench.add_case({fmt::format("slab a {:.3f} b {:g} g {:g} n {:g}", slab.albedo, slab.optical_thickness, slab.g, slab.refractive_index),
                                           "Rd", {slab.diffuse_reflectance, 0.0}, 1e-3,
                                           "adding-doubling (Prahl), data/reference/adding_doubling_slabs.csv, ~1e-3 relative"});
        bench.sweep_walk(index, BenchSolver::volumetric_walk, [&](std::uint64_t rays, std::uint64_t seed) {
            RteRequest request;
            request.stack = slab.stack();
            request.photons = rays;
            request.seed = seed;
            request.cancel = bench.options().cancel;
            return solve_rte(request).diffuse_reflectance;
        });
        // Similarity: sigma_s' = mu_s (1 - g); per cm, the slab 0.1 cm thick.
        const auto layer = slab.stack().layers.front();
        const double n = slab.refractive_index;
        const double entry = 1.0 - fresnel_reflectance(1.0, 1.0, n);
        const double face = n == 1.0 ? 0.0 : diffuse_fresnel_reflectance(n);
        const double reduced = layer.mu_s_per_cm * (1.0 - slab.g);
        bench.time_deterministic(index, BenchSolver::multipole, [&] {
            return entry * Multipole({reduced, layer.mu_a_per_cm, layer.thickness_cm, face, face}).total_reflectance();
        });
        bench.time_deterministic(index, BenchSolver::dipole, [&] { return entry * Dipole({reduced, layer.mu_a_per_cm, n}).total_reflectance(); });
        bench.time_deterministic(index, BenchSolver::adding_doubling, [&] { return solve_adding_doubling(slab.stack(), {}).diffuse_reflectance; });
    }
}

// The pigmentation presets at 550 nm: R by the BioSpec walk and both diffusion modes.
void preset_cases(Benchmark& bench) {
    for (const auto* name : {"biospec-lightly", "biospec-moderately", "biospec-heavily"}) {
        const auto material = load_material(name);
        const auto walk = [&](std::uint64_t rays, std::uint64_t seed) {
            SolverRequest request;
            request.spectral.max_rays_per_wavelength = rays;
            request.spectral.seed = seed;
            request.spectral.cancel = bench.options().cancel;
            const auto result = solve_spectrum(find_solver("biospec"), material, request);
            bench.check_cancel();  // a stopped walk may have finished no wavelength (front() of none crashed bench on Ctrl-C)
            return result.wavelengths.front().reflectance;
        };
        const auto index = bench.add_walk_reference_case(fmt::format("{} 550 nm", name), "R", walk, "BioSpec");
        bench.sweep_walk(index, BenchSolver::biospec_walk, walk);
        for (const auto mode : {DiffusionMode::multipole, DiffusionMode::dipole}) {
            const SolverRequest request;
            const auto& solver = find_solver(to_string(mode));
            const auto result = solve_spectrum(solver, material, request);
            bench.time_deterministic(index, mode == DiffusionMode::dipole ? BenchSolver::dipole : BenchSolver::multipole,
                                     [&] { return solve_spectrum(solver, material, request).wavelengths.front().reflectance.value; },
                                     trust_note(result));
        }
    }
}

// Jensen's skin1, G band, for the walk as `spectrum --mode rte` takes a band material (rte_band_slab): R total.
void jensen_case(Benchmark& bench) {
    const auto material = std::get<HomogeneousMaterial>(load_material("jensen2001-skin1"));
    const std::size_t band = 1;
    const auto walk = [&](std::uint64_t rays, std::uint64_t seed) {
        RteRequest request;
        request.stack = rte_band_slab(material, band);
        request.photons = rays;
        request.seed = seed;
        request.cancel = bench.options().cancel;
        const auto r = solve_rte(request);
        return Estimate{r.specular_reflectance.value + r.diffuse_reflectance.value, r.diffuse_reflectance.stderr};
    };
    const auto index = bench.add_walk_reference_case("jensen2001-skin1 G", "R", walk, "volumetric");
    bench.sweep_walk(index, BenchSolver::volumetric_walk, walk);
    for (const auto mode : {DiffusionMode::multipole, DiffusionMode::dipole}) {
        SpectralRequest request;
        bench.time_deterministic(index, mode == DiffusionMode::dipole ? BenchSolver::dipole : BenchSolver::multipole,
                                 [&] { return solve_diffusion_bands(material, request, {mode, std::nullopt}).wavelengths[band].reflectance.value; });
    }
}

// The multipole profile of the first slab (per cm) at 400 radii to 1 cm, pair tolerance 1e-1 ... 1e-10,
// against the series summed to 1e-14.
void pair_sweep(Benchmark& bench, const AddingDoublingSlab& slab) {
    bench.stage("multipole profile: pair tolerance sweep");
    const auto layer = slab.stack().layers.front();
    const double face = diffuse_fresnel_reflectance(slab.refractive_index);
    const DiffusionSlab d{layer.mu_s_per_cm * (1.0 - slab.g), layer.mu_a_per_cm, layer.thickness_cm, face, face};
    std::vector<double> radii;
    for (int i = 0; i < 400; ++i) radii.push_back(0.0025 * i);
    const auto exact = Multipole(d, 1e-14).reflectance_profile(radii);
    auto& report = bench.report();
    report.pair_sweep_radii = radii.size();
    for (const double tolerance : {1e-1, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
        const Multipole model(d, tolerance);
        RadialProfile profile;
        const double seconds = mean_seconds_per_call([&] { profile = model.reflectance_profile(radii); }, bench.plan().min_timing_seconds);
        double worst = 0.0;
        for (std::size_t i = 0; i < radii.size(); ++i) worst = std::max(worst, std::abs(profile.values[i] - exact.values[i]) / exact.values[i]);
        report.pair_sweep.push_back({tolerance, profile.max_pairs, seconds, worst});
        bench.check_cancel();
    }
}

void thread_scaling(Benchmark& bench, const AddingDoublingSlab& slab) {
    const auto rays = bench.plan().scaling_rays;
    bench.stage(fmt::format("thread scaling 1 -> 2 ({} rays)", rays));
    const auto material = load_material("biospec-moderately");
    const auto time_with = [&](int threads, const std::function<void()>& run) {
        const tbb::global_control control(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        const auto start = Clock::now();
        run();
        bench.check_cancel();
        return seconds_since(start);
    };
    const auto biospec = [&] {
        SolverRequest request;
        request.spectral.max_rays_per_wavelength = rays;
        request.spectral.cancel = bench.options().cancel;
        solve_spectrum(find_solver("biospec"), material, request);
    };
    const auto rte = [&] {
        RteRequest request;
        request.stack = slab.stack();
        request.photons = rays / 4;
        request.cancel = bench.options().cancel;
        solve_rte(request);
    };
    bench.report().scaling.push_back({BenchSolver::biospec_walk, "biospec-moderately 550 nm", rays, time_with(1, biospec), time_with(2, biospec)});
    bench.report().scaling.push_back({BenchSolver::volumetric_walk, "slab a 0.990 b 10.1 g 0.9 n 1.4", rays / 4, time_with(1, rte), time_with(2, rte)});
}

Lab lab_of(const SpectralResult& result, const TristimulusWeights& weights) {
    std::vector<double> r;
    for (const auto& w : result.wavelengths) r.push_back(w.reflectance.value);
    return xyz_to_lab(weights.integrate(r), weights.white());
}

// Each preset's spectrum by every solver on one thread, against the exact solution of the description it solves:
// the BioSpec walk against biospec-adding-doubling (the per-crossing model), the volumetric and reduced-scattering
// solvers against adding-doubling (mu_a, mu_s, phase); and the two descriptions against each other. Then the
// volumetric walk against adding-doubling at 550 nm in standard errors.
void skin_modes(Benchmark& bench) {
    const auto grid = WavelengthGrid::range(400.0, 700.0, 10.0);
    const TristimulusWeights weights(grid.nm(), IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    constexpr std::string_view volumetric_exact = "adding-doubling", biospec_exact = "biospec-adding-doubling";
    // Every registered solver for layered materials (a new one appears with no edit), the exact ones first.
    std::vector<std::string> solvers{std::string(biospec_exact), std::string(volumetric_exact)};
    for (const auto* s : solver_registry()) {
        if (s->name() == volumetric_exact || s->name() == biospec_exact || !s->capabilities().layered_materials) continue;
        if (s->name() == "rte" && !bench.plan().skin_volumetric_walk) continue;
        solvers.emplace_back(s->name());
    }
    // The presets' volumetric description is derived from their BioSpec one (model.volumetric_matched_to_biospec): adding-
    // doubling of it against biospec-adding-doubling is the one-skin row. Adding-doubling again on the layers' own
    // volumetric fields (the Salomatina mu_s', HG) shows the gap the derivation closes.
    const std::string own(own_description_row);
    solvers.insert(solvers.begin() + 2, own);
    // A solver that needs no extra description solves the BioSpec one.
    const auto reference_of = [&](const std::string& solver) -> std::string {
        if (solver == biospec_exact || solver == volumetric_exact || solver == own) return std::string(biospec_exact);
        return find_solver(solver).capabilities().material_needs.empty() ? std::string(biospec_exact) : std::string(volumetric_exact);
    };
    for (const auto& name : bench.plan().skin_presets) {
        const auto material = load_material(name);
        const auto own_material = load_material(name, {parse_override("model.volumetric_matched_to_biospec=false")});
        std::map<std::string, SpectralResult> results;
        for (const auto& solver : solvers) {
            bench.stage(fmt::format("{}: 400-700 nm by {} on one thread", name, solver));
            SolverRequest request;
            request.spectral.wavelengths = grid;
            request.spectral.cancel = bench.options().cancel;
            const auto& chosen = find_solver(solver == own ? volumetric_exact : solver);
            if (chosen.capabilities().uncertainty) {
                request.spectral.stderr_target = 0.002;
                request.spectral.max_rays_per_wavelength = 4'000'000;
            }
            SpectralResult result;
            const auto start = Clock::now();
            {
                const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                result = solve_spectrum(chosen, solver == own ? own_material : material, request);
            }
            const double seconds = seconds_since(start);
            bench.check_cancel();
            const auto reference = reference_of(solver);
            const auto& exact = results.count(reference) ? results.at(reference) : result;
            SkinModeRow row{name, solver, reference, seconds, 0, 0.0, 0.0, 1e300, -1e300, 0.0, 0.0, {}};
            for (std::size_t w = 0; w < grid.size(); ++w) {
                const auto& x = result.wavelengths[w];
                const auto& e = exact.wavelengths[w];
                row.rays += x.rays;
                row.uncertainty = std::max(row.uncertainty, x.reflectance.stderr);
                row.max_abs_error = std::max(row.max_abs_error, std::abs(x.reflectance.value - e.reflectance.value));
                const double exact_diffuse = e.reflectance.value - e.specular_reflectance.value;
                const double relative = (x.reflectance.value - x.specular_reflectance.value - exact_diffuse) / exact_diffuse;
                row.min_relative_diffuse_error = std::min(row.min_relative_diffuse_error, relative);
                row.max_relative_diffuse_error = std::max(row.max_relative_diffuse_error, relative);
            }
            if (!chosen.capabilities().uncertainty && result.stated_error && !result.stated_error->delta_e2000) row.uncertainty = result.stated_error->R;
            const auto a = lab_of(result, weights), b = lab_of(exact, weights);
            row.delta_e_ab = std::hypot(a.L - b.L, a.a - b.a, a.b - b.b);
            row.delta_e2000 = ciede2000(b, a);
            if (result.stated_error) row.stated_delta_e2000 = result.stated_error->delta_e2000;
            bench.report().skin_modes.push_back(row);
            results.emplace(solver, std::move(result));
        }
    }
    for (const auto& name : bench.plan().skin_presets) {
        const auto photons = bench.plan().agreement_photons;
        bench.stage(fmt::format("{}: volumetric walk at 550 nm, {} photons, against adding-doubling", name, photons));
        const auto material = load_material(name);
        SolverRequest request;
        request.fixed_rays_per_wavelength = photons;
        request.spectral.seed = bench.options().reference_seed;
        request.spectral.cancel = bench.options().cancel;
        const auto start = Clock::now();
        const auto walk = solve_spectrum(find_solver("rte"), material, request);
        const double seconds = seconds_since(start);
        bench.check_cancel();
        const auto& ad = find_solver("adding-doubling");
        const auto exact = solve_spectrum(ad, material, SolverRequest{});
        SolverRequest fine;
        constexpr std::size_t fine_channels = 96;
        fine.switches.quadrature_channels = fine_channels;
        const auto finer = solve_spectrum(ad, material, fine);
        bench.report().walk_agreement.push_back({name, 550.0, photons, walk.wavelengths.front().reflectance, exact.wavelengths.front().reflectance.value,
                                                 exact.stated_error->R, fine_channels,
                                                 finer.wavelengths.front().reflectance.value, seconds});
    }
}

// Every deterministic solver with radial profiles against the volumetric walk's R(r) on each preset.
void profile_agreement(Benchmark& bench) {
    constexpr double step_mm = 0.025, reach_mm = 5.0;
    std::vector<double> radii;
    for (int i = 0; i * step_mm <= reach_mm + 1e-9; ++i) radii.push_back(i * step_mm);
    const std::vector<double> wavelengths = bench.plan().quick_profiles ? std::vector<double>{550.0} : std::vector<double>{450.0, 550.0, 650.0};
    for (const auto& name : bench.plan().skin_presets) {
        const auto material = load_material(name);
        for (const double nm : wavelengths) {
            const auto photons = bench.plan().agreement_photons;
            bench.stage(fmt::format("{}: R(r) at {:g} nm, volumetric walk ({} photons) against the diffusion profiles", name, nm, photons));
            ProfileRequest request;
            request.wavelengths = WavelengthGrid::list({nm});
            request.radii_mm = radii;
            request.rays_per_wavelength = photons;
            request.seed = bench.options().reference_seed;
            request.cancel = bench.options().cancel;
            const auto start = Clock::now();
            const auto walk = solve_profiles(find_solver("rte"), material, request);
            const double walk_seconds = seconds_since(start);
            bench.check_cancel();
            const auto& w = walk.channels.front();
            for (const auto* solver : solver_registry()) {
                const auto& caps = solver->capabilities();
                if (!caps.radial_profiles || caps.uncertainty || !caps.layered_materials) continue;
                ProfileRequest deterministic;
                deterministic.wavelengths = request.wavelengths;
                deterministic.radii_mm = walk.radii_mm;
                const auto profiles = solve_profiles(*solver, material, deterministic);
                const auto& d = profiles.channels.front();
                ProfileAgreement row{name, nm, std::string(solver->name()), photons, 0, 0.0, 0.0, 0.0, 0.0, walk_seconds};
                std::vector<double> far;
                std::size_t within = 0;
                for (std::size_t i = 0; i < walk.radii_mm.size(); ++i) {
                    const double r = walk.radii_mm[i], value = w.reflectance_per_mm2[i];
                    if (r < 0.05 || r > reach_mm || !(value > 0.0) || w.reflectance_stderr_per_mm2[i] >= 0.05 * value) continue;
                    const double relative = (d.reflectance_per_mm2[i] - value) / value;
                    ++row.radii;
                    within += std::abs(relative) <= 0.15 ? 1 : 0;
                    if (std::abs(relative) > std::abs(row.worst_relative_error)) row.worst_relative_error = relative;
                    if (std::abs(r - 0.1) < 0.5 * step_mm) row.relative_error_at_0_1_mm = relative;
                    if (r >= 1.0) far.push_back(relative);
                }
                row.share_within_15_percent = row.radii ? static_cast<double>(within) / static_cast<double>(row.radii) : 0.0;
                if (!far.empty()) {
                    std::nth_element(far.begin(), far.begin() + static_cast<std::ptrdiff_t>(far.size() / 2), far.end());
                    row.median_relative_error_1_to_5_mm = far[far.size() / 2];
                }
                bench.report().profile_agreement.push_back(row);
            }
        }
    }
}

// The lit swatch `skinspec swatch --lit spot` renders by default (the exact transport) against matched-multipole's, one
// after the other on the same machine.
void lit_swatch_timings(Benchmark& bench) {
    const PatchGeometry view = lit_view(20.0, 256);
    const auto grid = WavelengthGrid::parse("400:700:10", "wavelengths");
    for (const auto& name : bench.plan().skin_presets) {
        const auto material = load_material(name);
        LitSwatchTiming row{name};
        for (const auto* solver : {&find_solver("matched-multipole"), &default_profile_solver()}) {
            bench.stage(fmt::format("{}: lit swatch (spot, 256 px, 31 wavelengths) by {}", name, solver->name()));
            const auto start = Clock::now();
            const auto patch = render_lit_patch(material, grid, Illumination::spot(2.0), view, *solver, ProfileRequest{}, image_geometry, {}, bench.options().cancel);
            const double seconds = seconds_since(start);
            bench.check_cancel();
            if (solver->capabilities().uncertainty) {
                row.exact_seconds = seconds;
                for (const auto& c : patch.profiles.channels) {
                    row.photons += c.rays;
                    row.within_radius_stderr = std::max(row.within_radius_stderr, c.within_radius_stderr);
                    row.converged = row.converged && c.converged;
                }
            } else {
                row.diffusion_seconds = seconds;
            }
        }
        bench.report().lit_swatches.push_back(row);
    }
}

void colour_timings(Benchmark& bench) {
    for (const auto& material : bench.plan().colour_materials) {
        bench.stage(fmt::format("{}: one swatch patch at Delta E <= 0.3", material));
        SwatchRequest request;
        request.material = material;
        request.cancel = bench.options().cancel;
        const auto start = Clock::now();
        const auto chart = compute_swatch(request);
        const double seconds = seconds_since(start);
        bench.check_cancel();
        const auto& patch = chart.patches.front();
        bench.report().colours.push_back({material, seconds, patch.rays, patch.uncertainty.delta_e2000, patch.converged});
    }
}

}  // namespace

// `export profile` of one member against a 16 x 16 melanosome x blood grid of it (issue 61 item 3), one after the other:
// the exact transport's profiles at the default precision over the RGB fit's wavelengths and the Gaussian fits. On
// the preset's own volumetric description (melanin and blood absorb only: one walk serves the grid, the exit replay);
// the description derived from the BioSpec one scales the dermis's scattering with them, so its members share no paths.
void profile_grid_timings(Benchmark& bench) {
    const auto base = load_material("biospec-moderately", {parse_override("model.volumetric_matched_to_biospec=false")});
    const auto axes = sweep_axes({parse_sweep("epidermis.melanosome_fraction=0.01:0.42:16:log"), parse_sweep("papillary_dermis.blood_fraction=0.002:0.05:16:log")});
    std::vector<Material> built;
    for (const auto& values : sweep_grid(axes)) {
        built.push_back(with_overrides(base, {parse_override(axes[0].field + "=" + fmt::format("{:.17g}", values[0])),
                                              parse_override(axes[1].field + "=" + fmt::format("{:.17g}", values[1]))}));
    }
    std::vector<const Material*> members;
    for (const auto& m : built) members.push_back(&m);
    ProfileRequest request;
    request.wavelengths = rgb_profile_wavelengths();
    for (int i = 0; i <= 1000; ++i) request.radii_mm.push_back(0.01 * i);
    request.cancel = bench.options().cancel;
    const ProfileExportRequest fit;
    const auto& solver = default_profile_solver();
    ProfileGridTiming row{"biospec-moderately (own volumetric description)", members.size()};
    bench.stage("biospec-moderately: export profile of one member");
    auto start = Clock::now();
    const auto one = solve_profiles(solver, *members[members.size() / 2], request);
    bench.check_cancel();
    fit_profile_export(one, false, fit);
    row.one_member_seconds = seconds_since(start);
    bench.stage(fmt::format("biospec-moderately: export profile of a 16 x 16 grid ({} members)", members.size()));
    start = Clock::now();
    const auto all = solve_profiles(solver, members, request);
    bench.check_cancel();
    const auto grid = fit_profile_export_grid(all, axes, false, fit);
    row.grid_seconds = seconds_since(start);
    for (const auto& c : all.front().channels) row.photons = std::max(row.photons, c.rays);
    for (const auto& m : grid.members) {
        for (const double e : m.fit.relative_l2_error) row.worst_profile_error = std::max(row.worst_profile_error, e);
    }
    for (const auto& p : all) {
        for (const auto& c : p.channels) row.within_radius_stderr = std::max(row.within_radius_stderr, c.within_radius_stderr);
    }
    bench.report().profile_grids.push_back(row);
}

BenchReport run_benchmark(const BenchOptions& options) {
    Benchmark bench(options);
    try {
        const auto slabs = adding_doubling_slabs();
        adding_doubling_cases(bench, slabs);
        preset_cases(bench);
        jensen_case(bench);
        pair_sweep(bench, slabs.front());
        thread_scaling(bench, slabs.front());
        colour_timings(bench);
        skin_modes(bench);
        profile_agreement(bench);
        lit_swatch_timings(bench);
        profile_grid_timings(bench);
    } catch (const Stopped&) {
        bench.report().partial = true;
    }
    return bench.report();
}

}  // namespace skinspec
