#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/layered_diffusion.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {
std::vector<double> radii_to(double r_max, double dr) {
    std::vector<double> radii;
    for (double r = 0.5 * dr; r < r_max; r += dr) radii.push_back(r);
    return radii;
}
double integral(const std::vector<double>& radii, const std::vector<double>& values, double dr) {
    double sum = 0.0;
    for (std::size_t i = 0; i < radii.size(); ++i) sum += 2.0 * std::numbers::pi * radii[i] * values[i] * dr;
    return sum;
}
}  // namespace

TEST_CASE("a one-slab stack is the slab", "[layered]") {
    const Multipole slab({2.0, 0.05, 3.0, 0.4, 0.2});
    const LayeredDiffusion stack({slab}, DiffusionBottom::open);
    CHECK(stack.total_reflectance() == Approx(slab.total_reflectance()).epsilon(1e-14));
    CHECK(stack.total_transmittance() == Approx(slab.total_transmittance()).epsilon(1e-14));
    const std::vector<double> radii{0.0, 0.5, 2.0};
    CHECK(stack.reflectance_profile(radii).values == slab.reflectance_profile(radii).values);
}

TEST_CASE("composition conserves energy without absorption", "[layered]") {
    // Kubelka-Munk in frequency space: at k = 0, R_a + T_a = 1 and R_b + T_b = 1 give R_ab + T_ab = 1.
    const LayeredDiffusion open({Multipole({2.0, 0.0, 1.0, 0.5, 0.01}), Multipole({0.5, 0.0, 4.0, 0.02, 0.3}),
                                 Multipole({5.0, 0.0, 0.8, 0.0, 0.5})},
                                DiffusionBottom::open);
    CHECK(open.total_reflectance() + open.total_transmittance() == Approx(1.0).epsilon(1e-12));
    // Over the reflector everything comes back (R1 R2 -> 1 in the series, still finite).
    const LayeredDiffusion mirror({Multipole({2.0, 0.0, 1.0, 0.5, 0.0}), Multipole({1.0, 0.0, 1e6, 0.0, 0.0})}, DiffusionBottom::reflector);
    CHECK(mirror.total_reflectance() == Approx(1.0).epsilon(1e-9));
    CHECK(mirror.total_transmittance() == 0.0);
}

TEST_CASE("composed profiles integrate to the composed totals", "[layered]") {
    const double f = diffuse_fresnel_reflectance(1.4);
    const LayeredDiffusion two({Multipole({2.0, 0.02, 1.0, f, 0.0}), Multipole({2.0, 0.02, 1.0, 0.0, f})}, DiffusionBottom::open);
    const LayeredDiffusion skin({Multipole({4.0, 0.5, 0.25, f, 0.0}), Multipole({2.5, 0.05, 0.5, 0.0, 0.0}),
                                 Multipole({2.5, 0.02, 1.8, 0.0, 0.0})},
                                DiffusionBottom::reflector);
    const double dr = 5e-3;
    const auto radii = radii_to(40.0, dr);
    for (const auto* stack : {&two, &skin}) {
        const auto r = stack->reflectance_profile(radii);
        const auto t = stack->transmittance_profile(radii);
        CHECK(r.converged);
        CHECK(integral(radii, r.values, dr) == Approx(stack->total_reflectance()).epsilon(2e-3));
        if (stack == &two) CHECK(integral(radii, t.values, dr) == Approx(stack->total_transmittance()).epsilon(2e-3));
    }
    // Splitting a slab into two equal halves with matched faces changes the totals only a little (diffusion
    // between the halves is what the composition approximates).
    const Multipole whole({2.0, 0.02, 2.0, f, f});
    CHECK(two.total_reflectance() == Approx(whole.total_reflectance()).margin(0.02));
    CHECK(two.total_transmittance() == Approx(whole.total_transmittance()).margin(0.02));
}

TEST_CASE("a partial reflector (the measured hypodermis) lies between an open matched bottom and the ideal reflector", "[layered]") {
    // Slabs whose bottom face is matched (internal reflectance 0), as the reflector and an open bottom of the same
    // index see them. rho = 0 keeps everything it receives: the open bottom's R and T, totals and profiles. rho = 1:
    // the ideal reflector. Without absorption, R + T = 1 at every rho (what the reflector keeps is T).
    const double f = diffuse_fresnel_reflectance(1.4);
    const std::vector<Multipole> slabs{Multipole({4.0, 0.5, 0.25, f, 0.0}), Multipole({2.5, 0.02, 1.8, 0.0, 0.0})};
    const LayeredDiffusion open(slabs, DiffusionBottom::open), black(slabs, DiffusionBottom::reflector, 0.0);
    const LayeredDiffusion ideal(slabs, DiffusionBottom::reflector), measured(slabs, DiffusionBottom::reflector, 0.5);
    CHECK(black.total_reflectance() == Approx(open.total_reflectance()).epsilon(1e-14));
    CHECK(black.total_transmittance() == Approx(open.total_transmittance()).epsilon(1e-14));
    const auto radii = radii_to(5.0, 0.05);
    const auto t_black = black.transmittance_profile(radii).values, t_open = open.transmittance_profile(radii).values;
    for (std::size_t i = 0; i < radii.size(); ++i) CHECK(t_black[i] == Approx(t_open[i]).epsilon(1e-9).margin(1e-14));
    CHECK(open.total_reflectance() < measured.total_reflectance());
    CHECK(measured.total_reflectance() < ideal.total_reflectance());
    CHECK(measured.total_transmittance() > 0.0);
    const LayeredDiffusion clear({Multipole({2.0, 0.0, 1.0, f, 0.0}), Multipole({1.0, 0.0, 2.0, 0.0, 0.0})}, DiffusionBottom::reflector, 0.3);
    CHECK(clear.total_reflectance() + clear.total_transmittance() == Approx(1.0).epsilon(1e-12));
    const double dr = 5e-3;
    const auto fine = radii_to(40.0, dr);
    CHECK(integral(fine, measured.transmittance_profile(fine).values, dr) == Approx(measured.total_transmittance()).epsilon(2e-3));
}

TEST_CASE("two thick, weakly absorbing layers: the composed multipole against adding-doubling", "[layered]") {
    // An external reference for the composition (Donner & Jensen 2005's Kubelka-Munk in frequency space): where
    // diffusion holds (albedo > 0.99, each layer many transport mean free paths thick, isotropic scattering, the
    // layers' indices matched, 1.4 against air), the composed total diffuse reflectance and transmittance must agree
    // with Prahl's adding-doubling of the same stack (radiative transfer, exact to its accuracy check) within the
    // diffusion approximation's own error here (a single slab's against adding-doubling says how much).
    const double eta = 1.4, fdr = diffuse_fresnel_reflectance(eta);
    struct Layer {
        double mu_s_per_mm, mu_a_per_mm, d_mm;
    };
    const Layer top{10.0, 0.02, 2.0}, bottom{6.0, 0.01, 6.0};  // albedos 0.998, 0.998; 20 and 36 mean free paths
    const LayeredDiffusion composed({Multipole({top.mu_s_per_mm, top.mu_a_per_mm, top.d_mm, fdr, 0.0}),
                                     Multipole({bottom.mu_s_per_mm, bottom.mu_a_per_mm, bottom.d_mm, 0.0, fdr})},
                                    DiffusionBottom::open);
    RteStack stack;
    for (const auto& l : {top, bottom}) stack.layers.push_back({eta, l.mu_a_per_mm * 10.0, l.mu_s_per_mm * 10.0, l.d_mm / 10.0, PhaseFunction::isotropic()});
    const auto ad = solve_adding_doubling(stack, AdIncidence{}, AdOptions{32, true});
    INFO("composed R " << composed.total_reflectance() << " T " << composed.total_transmittance() << "; adding-doubling R_d " << ad.diffuse_reflectance
                       << " T " << ad.transmittance << " (accuracy " << ad.accuracy << ")");
    CHECK(ad.accuracy < 1e-3);
    // Diffusion's own error on this kind of medium: each layer alone as one slab of the stack's whole thickness against
    // adding-doubling of it (+1.6 to +1.7 % in R, +5 to +6 % in T). The composition may add little to it.
    double worst_r = 0.0, worst_t = 0.0;
    for (const auto& l : {top, bottom}) {
        const Multipole alone({l.mu_s_per_mm, l.mu_a_per_mm, top.d_mm + bottom.d_mm, fdr, fdr});
        RteStack one;
        one.layers.push_back({eta, l.mu_a_per_mm * 10.0, l.mu_s_per_mm * 10.0, (top.d_mm + bottom.d_mm) / 10.0, PhaseFunction::isotropic()});
        const auto a = solve_adding_doubling(one, AdIncidence{}, AdOptions{32, true});
        worst_r = std::max(worst_r, std::abs(alone.total_reflectance() / a.diffuse_reflectance - 1.0));
        worst_t = std::max(worst_t, std::abs(alone.total_transmittance() / a.transmittance - 1.0));
    }
    CHECK(worst_r < 0.02);
    CHECK(std::abs(composed.total_reflectance() / ad.diffuse_reflectance - 1.0) <= worst_r + 0.005);
    CHECK(std::abs(composed.total_transmittance() / ad.transmittance - 1.0) <= worst_t + 0.03);
}

TEST_CASE("layered diffusion rejects impossible stacks", "[layered]") {
    const double inf = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(LayeredDiffusion({}, DiffusionBottom::open), Catch::Contains("has no slabs"));
    CHECK_THROWS_WITH(LayeredDiffusion({Multipole({1.0, 0.1, inf, 0.0, 0.0}), Multipole({1.0, 0.1, 1.0, 0.0, 0.0})}, DiffusionBottom::open),
                      Catch::Contains("slab 1 is semi-infinite but has slabs below it"));
    CHECK_THROWS_WITH(LayeredDiffusion({Multipole({1.0, 0.1, inf, 0.0, 0.0})}, DiffusionBottom::reflector),
                      Catch::Contains("semi-infinite but has a reflector below it"));
}
