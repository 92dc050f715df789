// Diffusion throughput (docs/PERFORMANCE.md), measured side by side in one run:
//  - a total diffuse reflectance: the dipole's closed form (Jensen et al. 2001 Sec. 2.4) and the multipole's
//    closed-form series; aim < 1 microsecond;
//  - a 1000-radius multipole profile (R(r) of a 10-mfp slab, 0-10 mm); aim < 5 ms;
//  - a three-layer composed profile (epidermis, papillary and reticular dermis over the reflector, 1000
//    radii, 0-10 mm); aim < 50 ms.
// Usage: skinspec_bench_diffusion
#include <chrono>
#include <vector>

#include <fmt/format.h>

#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/layered_diffusion.hpp"

using namespace skinspec;

namespace {
template <typename F>
double seconds_per_call(F&& f, int calls) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < calls; ++i) f(i);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / calls;
}
volatile double sink = 0.0;
}  // namespace

int main() {
    const double f = diffuse_fresnel_reflectance(1.4);
    const double t_dipole = seconds_per_call([&](int i) { sink = Dipole({1.0 + 1e-9 * i, 0.01, 1.4}).total_reflectance(); }, 2'000'000);
    const double t_multi_total =
        seconds_per_call([&](int i) { sink = Multipole({1.0 + 1e-9 * i, 0.01, 10.0, f, f}).total_reflectance(); }, 1'000'000);
    std::vector<double> radii;
    for (int i = 0; i < 1000; ++i) radii.push_back(0.01 * i);
    const Multipole slab({0.99, 0.01, 10.0, f, f});
    const double t_profile = seconds_per_call([&](int) { sink = slab.reflectance_profile(radii).values[10]; }, 200);
    const auto pairs = slab.reflectance_profile(radii).max_pairs;
    const LayeredDiffusion skin({Multipole({4.0, 0.5, 0.1, f, 0.0}), Multipole({2.5, 0.05, 0.2, 0.0, 0.0}),
                                 Multipole({2.5, 0.02, 1.8, 0.0, 0.0})},
                                DiffusionBottom::reflector);
    const double t_layered = seconds_per_call([&](int) { sink = skin.reflectance_profile(radii).values[10]; }, 40);
    const auto frequencies = skin.reflectance_profile(radii).frequencies;
    fmt::print("total Rd, dipole closed form:           {:10.3f} us   (aim < 1 us)\n", t_dipole * 1e6);
    fmt::print("total Rd, multipole series (10 mfp):    {:10.3f} us   (aim < 1 us)\n", t_multi_total * 1e6);
    fmt::print("multipole R(r), 1000 radii (10 mfp):    {:10.3f} ms   (aim < 5 ms; up to {} pairs)\n", t_profile * 1e3, pairs);
    fmt::print("three-layer composed R(r), 1000 radii:  {:10.3f} ms   (aim < 50 ms; {} frequency samples)\n", t_layered * 1e3, frequencies);
    return 0;
}
