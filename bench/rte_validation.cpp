// Accuracy validation of the volumetric walk (a long run, not a test): the six slabs of
// data/reference/adding_doubling_slabs.csv (made by scripts/make_data.py) at 1e7 photons each.
// Pass: every Rd and Tt within 3 standard errors and within 5e-4 absolute of the reference.
// Usage: skinspec_validate_rte [photons]   (default 10,000,000)
#include <chrono>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "formats/adding_doubling_reference.hpp"
#include "transport/rte/rte_model.hpp"

using namespace skinspec;

int main(int argc, char** argv) {
    const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10'000'000;
    bool all_pass = true;
    fmt::print("{:>9} {:>7} {:>4} {:>4} | {:>9} {:>9} {:>9} {:>6} | {:>9} {:>9} {:>9} {:>6} | {:>8} {}\n", "a", "b", "g", "n", "Rd", "ref",
               "stderr", "sigma", "Tt", "ref", "stderr", "sigma", "seconds", "pass");
    for (const auto& ref : adding_doubling_slabs()) {
        const double a = ref.albedo, b = ref.optical_thickness, g = ref.g, n = ref.refractive_index;
        const double rd = ref.diffuse_reflectance, tt = ref.total_transmittance;
        RteRequest request;
        request.stack = ref.stack();
        request.photons = photons;
        const auto start = std::chrono::steady_clock::now();
        const auto r = solve_rte(request);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const auto sig = [](double v, double expected, double se) { return se > 0 ? (v - expected) / se : (v == expected ? 0.0 : INFINITY); };
        const double s_rd = sig(r.diffuse_reflectance.value, rd, r.diffuse_reflectance.stderr);
        const double s_tt = sig(r.transmittance.value, tt, r.transmittance.stderr);
        const bool pass = std::abs(s_rd) <= 3 && std::abs(s_tt) <= 3 && std::abs(r.diffuse_reflectance.value - rd) <= 5e-4 &&
                          std::abs(r.transmittance.value - tt) <= 5e-4;
        all_pass = all_pass && pass;
        fmt::print("{:>9} {:>7} {:>4} {:>4} | {:>9.6f} {:>9.6f} {:>9.6f} {:>6.2f} | {:>9.6f} {:>9.6f} {:>9.6f} {:>6.2f} | {:>8.1f} {}\n", a, b, g,
                   n, r.diffuse_reflectance.value, rd, r.diffuse_reflectance.stderr, s_rd, r.transmittance.value, tt, r.transmittance.stderr,
                   s_tt, seconds, pass ? "yes" : "NO");
    }
    fmt::print("{} photons per case: {}\n", photons, all_pass ? "all within 3 standard errors and 5e-4" : "SOME CASES FAIL");
    return all_pass ? 0 : 1;
}
