// Accuracy validation of the volumetric walk (a long run, not a test): the six slabs of
// ../shared/reference/adding_doubling_slabs.csv (copied to tests/reference) at 1e7 photons each.
// Pass: every Rd and Tt within 3 standard errors and within 5e-4 absolute of the reference.
// Usage: skinspec_validate_rte [photons]   (default 10,000,000)
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "layers/rte/rte_model.hpp"

using namespace skinspec;

int main(int argc, char** argv) {
    const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10'000'000;
    std::ifstream in(SKINSPEC_REFERENCE_DIR "/adding_doubling_slabs.csv");
    std::string line;
    bool all_pass = true;
    fmt::print("{:>9} {:>7} {:>4} {:>4} | {:>9} {:>9} {:>9} {:>6} | {:>9} {:>9} {:>9} {:>6} | {:>8} {}\n", "a", "b", "g", "n", "Rd", "ref",
               "stderr", "sigma", "Tt", "ref", "stderr", "sigma", "seconds", "pass");
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#' || line[0] == 'a') continue;
        for (auto& c : line) c = c == ',' ? ' ' : c;
        std::istringstream row(line);
        double a, b, g, n, rd, tt, absorbed;
        row >> a >> b >> g >> n >> rd >> tt >> absorbed;
        const double d = 0.1, mu_t = b / d;
        RteRequest request;
        request.stack.layers.push_back({n, mu_t * (1 - a), mu_t * a, d, PhaseFunction::henyey_greenstein(g)});
        request.photons = photons;
        const auto start = std::chrono::steady_clock::now();
        const auto r = solve_rte(request);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const auto sig = [](double v, double ref, double se) { return se > 0 ? (v - ref) / se : (v == ref ? 0.0 : INFINITY); };
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
