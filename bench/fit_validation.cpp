// The synthetic round trip of Mukaigawa et al. 2009 Sec. 4.1 (compare with its Table 2) and a fit of a volumetric-walk
// profile (docs/PROFILE_FIT.md). A long run, not a test.
//  1. 64 x 64 = 4096 patches at 0.05 mm, non-uniform light, dipole sigma_s' 2.19, sigma_a 0.002 /mm, eta 1.3;
//     quantisation steps 0.05-0.50 mm: grid estimate, refined estimate, PSNR of the re-synthesised image;
//     then the same with 1 % multiplicative noise on the observation.
//  2. Planar input of 100 x 100 = 10^4 patches end to end (system, W+ l, fit, re-synthesis): time.
//  3. The volumetric walk's R(r) of a semi-infinite medium (sigma_s' 2.19, sigma_a 0.02 /mm, isotropic,
//     n = 1.3) fitted with and without its measured total diffuse reflectance.
// Usage: skinspec_validate_fit [photons]
#include <chrono>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>

#include "inverse/profile_fit/dipole_fit.hpp"
#include "inverse/profile_fit/profile_solve.hpp"
#include "inverse/profile_fit/synthetic_scene.hpp"
#include "transport/rte/rte_model.hpp"

using namespace skinspec;

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void round_trip_table(double noise) {
    SyntheticSceneSpec spec;
    spec.noise = noise;
    const auto scene = synthetic_planar_scene(spec);
    fmt::print("\nnoise {:g} %: step_mm | grid sigma_s' sigma_a | refined sigma_s' (err) sigma_a | PSNR dB | bins | s\n", 100 * noise);
    for (int k = 1; k <= 10; ++k) {
        const double step = 0.05 * k;
        const auto start = std::chrono::steady_clock::now();
        const auto system = planar_system(scene, step);
        const auto estimate = solve_profile(system);
        const auto fit = fit_dipole(estimate.distances_mm, estimate.profile_per_mm2, estimate.has_data, {});
        const Dipole fitted({fit.reduced_scattering_per_mm, fit.absorption_per_mm, 1.3});
        const auto again = render_planar(scene, [&](double x) { return fitted.radial_reflectance(x); });
        fmt::print("  {:5.2f} | {:5.2f} {:6.3f} | {:7.4f} ({:+5.1f} %) {:8.5f} | {:6.2f} | {:4} | {:.2f}\n", step, fit.grid_reduced_scattering_per_mm,
                   fit.grid_absorption_per_mm, fit.reduced_scattering_per_mm, 100.0 * (fit.reduced_scattering_per_mm / 2.19 - 1.0),
                   fit.absorption_per_mm, psnr_db(scene.observed, again, scene.valid), system.bins(), seconds_since(start));
    }
}
}  // namespace

int main(int argc, char** argv) {
    const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1'000'000;
    fmt::print("1. Synthetic round trip (64 x 64 patches at 0.05 mm; truth sigma_s' 2.19, sigma_a 0.002 /mm, eta 1.3)\n");
    round_trip_table(0.0);
    round_trip_table(0.01);

    SyntheticSceneSpec big;
    big.width = big.height = 100;
    const auto start = std::chrono::steady_clock::now();
    const auto scene = synthetic_planar_scene(big);
    const double t_render = seconds_since(start);
    const auto t0 = std::chrono::steady_clock::now();
    const auto system = planar_system(scene, 0.1);
    const double t_system = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const auto estimate = solve_profile(system);
    const double t_solve = seconds_since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    const auto fit = fit_dipole(estimate.distances_mm, estimate.profile_per_mm2, estimate.has_data, {});
    const Dipole fitted({fit.reduced_scattering_per_mm, fit.absorption_per_mm, 1.3});
    const auto again = render_planar(scene, [&](double x) { return fitted.radial_reflectance(x); });
    const double t_fit = seconds_since(t2);
    fmt::print("\n2. 10^4 patches (100 x 100, step 0.1 mm, {} bins): system {:.2f} s, W+ l {:.2f} s, fit + re-synthesis {:.2f} s; "
               "end to end {:.2f} s (aim < 5 s; rendering the input took {:.2f} s); sigma_s' {:.4f}, PSNR {:.1f} dB\n",
               system.bins(), t_system, t_solve, t_fit, t_system + t_solve + t_fit, t_render, fit.reduced_scattering_per_mm,
               psnr_db(scene.observed, again, scene.valid));

    RteRequest request;
    request.stack.layers.push_back({1.3, 0.2, 21.9, 10.0, PhaseFunction::isotropic()});  // per cm; 100 mm deep
    request.photons = photons;
    request.grid = {0.01, 0.005, 1, 200, 0};  // R(r) in 0.05 mm rings to 10 mm
    const auto walk = solve_rte(request);
    std::vector<double> d, r;
    std::vector<char> use;
    for (std::size_t i = 0; i < walk.reflectance_r.size(); ++i) {
        d.push_back((i + 0.5) * 0.05);
        r.push_back(walk.reflectance_r[i].value / 100.0);  // 1/cm^2 -> 1/mm^2
        use.push_back(1);
    }
    const double rd = walk.diffuse_reflectance.value / (1.0 - walk.specular_reflectance.value);  // per entering photon
    DipoleFitOptions options;
    options.reduced_scattering_per_mm = {0.01, 5.0, 0.01};
    options.absorption_per_mm = {0.0, 0.1, 0.001};
    fmt::print("\n3. Volumetric walk R(r), {} photons (truth sigma_s' 2.19, sigma_a 0.02 /mm, n 1.3; walk Rd {:.4f} +- {:.4f}):\n", photons, rd,
               walk.diffuse_reflectance.stderr);
    // Near the entry point the walk's profile is single scattering, which the dipole does not model: the
    // fit is shown from 0 and from 1 and 2 mm (2 and 4 transport mean free paths) on.
    for (const double from : {0.0, 1.0, 2.0}) {
        for (std::size_t i = 0; i < d.size(); ++i) use[i] = d[i] >= from ? 1 : 0;
        options.total_diffuse_reflectance.reset();
        const auto free_fit = fit_dipole(d, r, use, options);
        options.total_diffuse_reflectance = rd;
        const auto total_fit = fit_dipole(d, r, use, options);
        fmt::print("   r >= {:g} mm: free fit sigma_s' {:.4f}, sigma_a {:.5f} /mm; with the walk's Rd: sigma_s' {:.4f}, sigma_a {:.5f} /mm\n",
                   from, free_fit.reduced_scattering_per_mm, free_fit.absorption_per_mm, total_fit.reduced_scattering_per_mm,
                   total_fit.absorption_per_mm);
    }
    return 0;
}
