// Benchmark of the BioSpec walk (issue: performance evidence). Measures, side by side in one run:
//  1. rays per second at 550 nm, moderately pigmented preset, reflector on, on 1 thread and on 2 threads;
//  2. the time of a full 400-700 nm / 10 nm spectrum at standard error <= 0.002 per wavelength on 2 threads.
// Each figure is the best of `repeats` runs (this machine's timings vary 10-30 % from run to run), with the
// median beside it. Also the instruction set the walk's packets run on.
// Usage: skinspec_bench_biospec [rays] [repeats] [instruction set]   (default 4,000,000 rays for the throughput runs,
// 5 repeats, the best instruction set the machine has; e.g. AVX2 measures an AVX2 machine's code path on an AVX-512 one)
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#include <hwy/targets.h>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "bench/bench_timing.hpp"
#include "transport/biospec/biospec_packet.hpp"
#include "transport/biospec/biospec_solver.hpp"
#include "materials/material_file.hpp"

using namespace skinspec;
using skinspec::bench::seconds_of;

namespace {

struct Timing {
    double best_s;
    double median_s;
};

Timing repeated(int repeats, const std::function<void()>& run) {
    std::vector<double> s;
    for (int i = 0; i < repeats; ++i) s.push_back(seconds_of(run));
    std::sort(s.begin(), s.end());
    return {s.front(), s[s.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
    const std::uint64_t rays = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 4'000'000;
    const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
    if (argc > 3) {
        std::string names;
        bool found = false;
        for (const auto target : hwy::SupportedAndGeneratedTargets()) {
            names += std::string(names.empty() ? "" : ", ") + hwy::TargetName(target);
            if (std::string(hwy::TargetName(target)) == argv[3]) {
                hwy::SetSupportedTargetsForTest(target);
                found = true;
            }
        }
        if (!found) {
            fmt::print(stderr, "instruction set '{}' is not one this machine runs (allowed: {})\n", argv[3], names);
            return 2;
        }
    }
    fmt::print("packets on {} (best of {} runs, median in brackets)\n", biospec_packet_target(), repeats);
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({550.0});
    request.max_rays_per_wavelength = rays;

    solve_biospec(stack, request);  // warm-up: data tables loaded
    double per_thread_count[3] = {0, 0, 0};
    for (const int threads : {1, 2}) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
        const auto t = repeated(repeats, [&] { solve_biospec(stack, request); });
        per_thread_count[threads] = static_cast<double>(rays) / t.best_s;
        fmt::print("550 nm, biospec-moderately, reflector on, {} thread(s): {:.3g} rays/s total, {:.3g} rays/s per core ({:.3g})\n",
                   threads, per_thread_count[threads], per_thread_count[threads] / threads, static_cast<double>(rays) / t.median_s / threads);
    }
    fmt::print("speed-up 1 -> 2 threads: {:.2f}x (hardware threads: {})\n", per_thread_count[2] / per_thread_count[1],
               std::thread::hardware_concurrency());

    SpectralRequest spectrum;
    spectrum.wavelengths = WavelengthGrid::range(400.0, 700.0, 10.0);
    spectrum.stderr_target = 0.002;
    spectrum.max_rays_per_wavelength = 10'000'000;
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, 2);
    SpectralResult result;
    const auto t = repeated(repeats, [&] { result = solve_biospec(stack, spectrum); });
    std::uint64_t total = 0;
    double worst = 0.0;
    for (const auto& w : result.wavelengths) {
        total += w.rays;
        worst = std::max(worst, w.reflectance.stderr);
    }
    fmt::print("400-700 nm / 10 nm spectrum at stderr <= 0.002 on 2 threads: {:.3f} s ({:.3f}), {} rays, worst stderr {:.4f}\n", t.best_s,
               t.median_s, total, worst);
    return 0;
}
