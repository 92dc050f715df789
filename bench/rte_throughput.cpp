// Throughput of the volumetric walk on the cases MCML 1.2 is compared on (the slab mu_a 1, mu_s 100 /cm, g 0.9,
// d 0.1 cm, n 1.4; sample.mci's first run; a 7-layer skin at 600 nm), with MCML's grids, on 1 and 2 threads side
// by side. MCML itself is built and timed outside this repository (docs/PERFORMANCE.md, "Side by side").
// Usage: skinspec_bench_rte [photons scale]   (default 1)
#include <chrono>
#include <cstdlib>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "formats/mcml_files.hpp"
#include "transport/rte/rte_packet.hpp"
#include "spectral/data_paths.hpp"

using namespace skinspec;

int main(int argc, char** argv) {
    const double scale = argc > 1 ? std::atof(argv[1]) : 1.0;
    struct Case { const char* name; RteStack stack; std::uint64_t photons; RteGrid grid; };
    std::vector<Case> cases;
    RteStack slab;
    slab.layers.push_back({1.4, 1.0, 100.0, 0.1, PhaseFunction::henyey_greenstein(0.9)});
    cases.push_back({"slab (1/100/0.9/0.1, n 1.4)", slab, 2'000'000, RteGrid{0.01, 0.01, 40, 50, 30}});
    cases.push_back({"slab, grids off (spectrum's way)", slab, 2'000'000, RteGrid{}});
    const auto sample = read_mci(data_file("mcml/sample.mci")).front();
    cases.push_back({"sample.mci run 1 (3 layers)", sample.stack, 1'000'000, sample.grid});
    RteStack skin;
    const double layers[7][5] = {{1.53, 0.2, 1000, 0.9, 0.002}, {1.34, 0.15, 400, 0.85, 0.008}, {1.4, 0.7, 300, 0.8, 0.01},
                                 {1.39, 1, 350, 0.9, 0.008},    {1.4, 0.7, 200, 0.76, 0.162},  {1.39, 1, 350, 0.95, 0.02},
                                 {1.44, 0.3, 150, 0.8, 0.59}};
    for (const auto& l : layers) skin.layers.push_back({l[0], l[1], l[2], l[4], PhaseFunction::henyey_greenstein(l[3])});
    cases.push_back({"7-layer skin at 600 nm", skin, 100'000, RteGrid{0.01, 0.01, 40, 50, 30}});
    fmt::print("packets on {}\n", rte_packet_target());
    for (auto& c : cases) {
        const auto photons = static_cast<std::uint64_t>(static_cast<double>(c.photons) * scale);
        double rate[3] = {0, 0, 0};
        for (const int threads : {1, 2}) {
            tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
            RteRequest r;
            r.stack = c.stack;
            r.photons = photons;
            r.grid = c.grid;
            const auto start = std::chrono::steady_clock::now();
            solve_rte(r);
            rate[threads] = static_cast<double>(photons) / std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        fmt::print("{:<34} 1 thread {:>9.3g} photons/s; 2 threads {:>9.3g} photons/s ({:.2f}x scaling)\n", c.name, rate[1], rate[2],
                   rate[2] / rate[1]);
    }
    return 0;
}
