// Accuracy of the diffusion models against the volumetric walk (a long run, not a test; docs/DIFFUSION.md):
//  1. slabs of 2, 10 and 20 transport mean free paths (mfp 1 mm, reduced albedo 0.99, isotropic scattering),
//     matched (n = 1) and mismatched (n = 1.4) boundaries, as in Donner & Jensen 2005 Fig. 2 / Table 1: total R and T and
//     R(r), T(r) at 0.5, 1, 2 and 4 mm, for the dipole and the multipole;
//  2. a semi-infinite medium (a 200 mfp slab for the walk) at reduced albedo 0.99, 0.9 and 0.5, n = 1.3:
//     where the dipole agrees and where diffusion breaks down.
// The walk's standard errors are printed with its values. Usage: skinspec_validate_diffusion [photons]
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/multipole.hpp"
#include "transport/fresnel.hpp"
#include "transport/rte/rte_model.hpp"

using namespace skinspec;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
const std::vector<double> probe_radii_mm{0.5, 1.0, 2.0, 4.0};

struct Walk {
    RteResult result;
    double dr_mm;
    double seconds;
};

// One slab (per mm, thickness mm) through the volumetric walk, radial tallies in 0.1 mm rings to 10 mm.
Walk walk(double sigma_s, double sigma_a, double thickness_mm, double n, std::uint64_t photons) {
    RteRequest request;
    request.stack.layers.push_back({n, sigma_a * 10.0, sigma_s * 10.0, thickness_mm / 10.0, PhaseFunction::isotropic()});
    request.photons = photons;
    request.grid = {0.01, 0.01, 1, 100, 0};
    const auto start = std::chrono::steady_clock::now();
    auto result = solve_rte(request);
    return {std::move(result), 0.1, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

// The walk's ring at radius r (per mm^2; MCML's 1/cm^2 / 100).
Estimate ring(const std::vector<Estimate>& per_cm2, double dr_mm, double r_mm) {
    const auto i = static_cast<std::size_t>(r_mm / dr_mm);
    return {per_cm2[i].value / 100.0, per_cm2[i].stderr / 100.0};
}

// The diffusion profile averaged over the same ring as the walk's bin.
template <typename F>
double ring_average(F&& profile, double dr_mm, double r_mm) {
    const auto i = static_cast<double>(static_cast<std::size_t>(r_mm / dr_mm));
    const double r0 = i * dr_mm;
    double sum = 0.0, area = 0.0;
    for (int k = 0; k < 64; ++k) {
        const double r = r0 + (k + 0.5) * dr_mm / 64;
        sum += profile(r) * r;
        area += r;
    }
    return sum / area;
}

std::string percent(double model, double reference) {
    return reference != 0.0 ? fmt::format("{:+.1f}%", 100.0 * (model - reference) / reference) : std::string("n/a");
}

}  // namespace

int main(int argc, char** argv) {
    const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1'000'000;
    fmt::print("Diffusion against the volumetric walk ({} photons per case; walk values +- one standard error)\n\n", photons);

    fmt::print("1. Slabs, mfp 1 mm, reduced albedo 0.99 (sigma_s' 0.99/mm, sigma_a 0.01/mm), isotropic\n");
    fmt::print("{:>4} {:>4} {:>4} | {:>18} {:>8} {:>8} {:>8} {:>8} | {:>18} {:>8} {:>8} {:>8} {:>8} | {:>6}\n", "mfp", "n", "qty", "walk",
               "dipole", "err", "multi", "err", "", "", "", "", "", "s");
    for (const double n : {1.0, 1.4}) {
        for (const double d : {2.0, 10.0, 20.0}) {
            const auto w = walk(0.99, 0.01, d, n, photons);
            const double entry = 1.0 - fresnel_reflectance(1.0, 1.0, n);
            const double f = n == 1.0 ? 0.0 : diffuse_fresnel_reflectance(n);
            const Multipole multi({0.99, 0.01, d, f, f});
            const Multipole dipole({0.99, 0.01, inf, f, 0.0});
            const auto line = [&](const std::string& what, Estimate walk_value, double dipole_value, double multi_value) {
                fmt::print("{:>4g} {:>4g} {:>6} | {:>9.5f} +- {:<7.5f} {:>8.5f} {:>8} {:>8.5f} {:>8}\n", d, n, what, walk_value.value,
                           walk_value.stderr, dipole_value, percent(dipole_value, walk_value.value), multi_value,
                           percent(multi_value, walk_value.value));
            };
            line("R", w.result.diffuse_reflectance, entry * dipole.total_reflectance(), entry * multi.total_reflectance());
            line("T", w.result.transmittance, 0.0, entry * multi.total_transmittance());
            for (const double r : probe_radii_mm) {
                line(fmt::format("R({:g})", r), ring(w.result.reflectance_r, w.dr_mm, r),
                     entry * ring_average([&](double x) { return dipole.radial_reflectance(x); }, w.dr_mm, r),
                     entry * ring_average([&](double x) { return multi.radial_reflectance(x); }, w.dr_mm, r));
            }
            for (const double r : probe_radii_mm) {
                line(fmt::format("T({:g})", r), ring(w.result.transmittance_r, w.dr_mm, r), 0.0,
                     entry * ring_average([&](double x) { return multi.radial_transmittance(x); }, w.dr_mm, r));
            }
            fmt::print("     (walk {:.1f} s)\n", w.seconds);
        }
    }

    fmt::print("\n2. Semi-infinite medium (walk: 200 mfp slab), mfp 1 mm, n = 1.3, isotropic\n");
    for (const double albedo : {0.99, 0.9, 0.5}) {
        const auto w = walk(albedo, 1.0 - albedo, 200.0, 1.3, photons);
        const double entry = 1.0 - fresnel_reflectance(1.0, 1.0, 1.3);
        const Dipole dipole({albedo, 1.0 - albedo, 1.3});
        const auto line = [&](const std::string& what, Estimate walk_value, double model) {
            fmt::print("{:>5g} {:>6} | {:>9.5f} +- {:<7.5f} dipole {:>8.5f} {:>8}\n", albedo, what, walk_value.value, walk_value.stderr, model,
                       percent(model, walk_value.value));
        };
        line("R", w.result.diffuse_reflectance, entry * dipole.total_reflectance());
        for (const double r : probe_radii_mm) {
            line(fmt::format("R({:g})", r), ring(w.result.reflectance_r, w.dr_mm, r),
                 entry * ring_average([&](double x) { return dipole.radial_reflectance(x); }, w.dr_mm, r));
        }
        fmt::print("      (walk {:.1f} s)\n", w.seconds);
    }
    return 0;
}
