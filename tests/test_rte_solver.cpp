#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <tbb/global_control.h>

#include "formats/adding_doubling_reference.hpp"
#include "materials/material_file.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"
#include "spectral/input_error.hpp"
#include "exponential_integral.hpp"

using namespace skinspec;

namespace {

RteRequest slab(double mu_a, double mu_s, double g, double d, double n, std::uint64_t photons) {
    RteRequest r;
    r.stack.layers.push_back({n, mu_a, mu_s, d, PhaseFunction::henyey_greenstein(g)});
    r.photons = photons;
    return r;
}

double energy(const RteResult& r) {
    return r.specular_reflectance.value + r.diffuse_reflectance.value + r.transmittance.value + r.absorbed.value;
}

}  // namespace

TEST_CASE("all six adding-doubling slabs are reproduced within statistical error", "[rte_solver]") {
    // data/reference/adding_doubling_slabs.csv (Prahl's adding-doubling, ~1e-3 relative).
    int cases = 0;
    for (const auto& ref : adding_doubling_slabs()) {
        RteRequest request;
        request.stack = ref.stack();
        request.photons = 200'000;
        const auto r = solve_rte(request);
        INFO("a " << ref.albedo << " b " << ref.optical_thickness << " g " << ref.g << " n " << ref.refractive_index);
        // 4 standard errors plus the reference's own ~1e-3 relative accuracy.
        const double rd = ref.diffuse_reflectance, tt = ref.total_transmittance;
        CHECK(std::abs(r.diffuse_reflectance.value - rd) < 4.0 * r.diffuse_reflectance.stderr + 1e-3 * rd);
        CHECK(std::abs(r.transmittance.value - tt) < 4.0 * r.transmittance.stderr + 1e-3 * tt + 1e-12);
        CHECK(energy(r) == Approx(1.0).margin(1e-12));
        ++cases;
    }
    CHECK(cases == 6);
}

TEST_CASE("analytic limits: specular reflection, Beer-Lambert, no absorption", "[rte_solver]") {
    // Specular: ((n - 1) / (n + 1))^2 at normal incidence.
    const auto glassy = solve_rte(slab(1.0, 10.0, 0.5, 0.1, 1.5, 1000));
    CHECK(glassy.specular_reflectance.value == Approx(0.04).margin(1e-15));
    // No scattering, matched: T = exp(-mu_a d) (Beer-Lambert), R = 0.
    const auto clear = solve_rte(slab(3.0, 0.0, 0.0, 0.2, 1.0, 200'000));
    CHECK(std::abs(clear.transmittance.value - std::exp(-0.6)) < 4.0 * clear.transmittance.stderr);
    CHECK(clear.diffuse_reflectance.value == 0.0);
    // No absorption: everything leaves.
    const auto white = solve_rte(slab(0.0, 50.0, 0.0, 0.1, 1.0, 20'000));
    CHECK(white.diffuse_reflectance.value + white.transmittance.value == Approx(1.0).margin(1e-12));
    // Split and all-or-none boundaries agree.
    auto split = slab(1.0, 100.0, 0.9, 0.1, 1.4, 100'000);
    split.boundaries = BoundaryMode::split;
    const auto a = solve_rte(split);
    const auto b = solve_rte(slab(1.0, 100.0, 0.9, 0.1, 1.4, 100'000));
    CHECK(std::abs(a.diffuse_reflectance.value - b.diffuse_reflectance.value) <
          4.0 * std::hypot(a.diffuse_reflectance.stderr, b.diffuse_reflectance.stderr));
}

TEST_CASE("the walk over a reflector of reflectance rho under a clear absorber: R = rho e^-tau 2 E_3(tau), T = (1 - rho) e^-tau", "[rte_solver]") {
    // Matched media: the photon reaches the reflector with probability e^-tau, stays in it with 1 - rho (T, the
    // hypodermis' share) or returns Lambertian and crosses the layer with probability 2 E_3(tau).
    auto request = slab(4.0, 0.0, 0.0, 0.1, 1.0, 200'000);
    request.stack.bottom_reflector = true;
    request.stack.bottom_reflectance = 0.35;
    const auto r = solve_rte(request);
    CHECK(std::abs(r.diffuse_reflectance.value - 0.35 * std::exp(-0.4) * 2.0 * skinspec::testing::exponential_integral_3(0.4)) < 4.0 * r.diffuse_reflectance.stderr);
    CHECK(std::abs(r.transmittance.value - 0.65 * std::exp(-0.4)) < 4.0 * r.transmittance.stderr);
    CHECK(energy(r) == Approx(1.0).margin(1e-9));
}

TEST_CASE("radial and angular tallies integrate to the totals", "[rte_solver]") {
    auto r = slab(1.0, 100.0, 0.9, 0.1, 1.4, 50'000);
    r.grid = RteGrid{0.005, 0.01, 20, 30, 10};
    const auto res = solve_rte(r);
    double rd = 0.0, tt = 0.0, az = 0.0, ra = 0.0;
    for (std::size_t ir = 0; ir < 30; ++ir) {
        const double area = 2.0 * std::numbers::pi * (ir + 0.5) * 0.01 * 0.01;
        rd += res.reflectance_r[ir].value * area;
        tt += res.transmittance_r[ir].value * area;
    }
    for (const auto& a : res.absorption_z) az += a.value * 0.005;
    const double da = 0.5 * std::numbers::pi / 10;
    for (std::size_t ia = 0; ia < 10; ++ia) ra += res.reflectance_a[ia].value * 2.0 * std::numbers::pi * std::sin((ia + 0.5) * da) * da;
    CHECK(rd == Approx(res.diffuse_reflectance.value).epsilon(1e-12));
    CHECK(tt == Approx(res.transmittance.value).epsilon(1e-12));
    CHECK(az == Approx(res.absorbed.value).epsilon(1e-12));
    CHECK(ra == Approx(res.diffuse_reflectance.value).epsilon(1e-12));
}

TEST_CASE("the volumetric walk is identical on 1 and 2 threads", "[rte_solver]") {
    const auto run = [](int threads) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
        auto r = slab(1.0, 100.0, 0.9, 0.1, 1.4, 30'000);
        r.grid = RteGrid{0.01, 0.01, 5, 5, 5};
        return solve_rte(r);
    };
    const auto one = run(1), two = run(2);
    CHECK(one.diffuse_reflectance.value == two.diffuse_reflectance.value);
    CHECK(one.transmittance.stderr == two.transmittance.stderr);
    CHECK(one.absorption_rz[7].value == two.absorption_rz[7].value);
}

TEST_CASE("stress: extreme optics finish finite, in [0, 1], energy conserved, bounded", "[rte_solver]") {
    struct Case { double mu_a, mu_s, g, d, n; };
    std::vector<Case> cases;
    for (const double g : {-0.999, 0.0, 0.999, 1.0 - 1e-9})
        for (const double albedo : {0.0, 1e-6, 0.5, 0.999999, 1.0}) cases.push_back({100.0 * (1 - albedo), 100.0 * albedo, g, 0.05, 1.4});
    cases.push_back({1.0, 100.0, 0.9, 1e-9, 1.4});     // a billionth of a cm
    cases.push_back({0.0, 100.0, 0.9, 10.0, 1.4});     // 1e3 mean free paths, albedo 1
    cases.push_back({1.0, 100.0, 0.9, 0.1, 3.0});      // n = 3
    cases.push_back({1.0, 0.0, 0.9, 0.1, 1.0});        // mu_s = 0 with g != 0
    for (const auto& c : cases) {
        INFO("mu_a " << c.mu_a << " mu_s " << c.mu_s << " g " << c.g << " d " << c.d << " n " << c.n);
        auto r = slab(c.mu_a, c.mu_s, c.g, c.d, c.n, 500);
        r.max_steps_per_photon = 2'000'000;
        const auto start = std::chrono::steady_clock::now();
        const auto res = solve_rte(r);
        CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 20.0);
        for (const double v : {res.diffuse_reflectance.value, res.transmittance.value, res.absorbed.value}) {
            CHECK(std::isfinite(v));
            CHECK(v >= -1e-12);
            CHECK(v <= 1.0 + 1e-12);
        }
        CHECK(energy(res) == Approx(1.0).margin(1e-12));
    }
}

TEST_CASE("a photon that cannot finish is stopped and reported", "[rte_solver]") {
    auto r = slab(0.0, 100.0, 0.0, 10.0, 1.0, 50);
    r.max_steps_per_photon = 100;
    const auto res = solve_rte(r);
    CHECK(res.truncated_photons > 0);
    CHECK(energy(res) == Approx(1.0).margin(1e-12));
}

TEST_CASE("bad volumetric inputs are input errors", "[rte_solver]") {
    CHECK_THROWS_WITH(solve_rte(slab(-1.0, 1.0, 0.0, 0.1, 1.4, 10)), Catch::Contains("layer 1 mu_a [1/cm] = -1 is outside [0, inf)"));
    CHECK_THROWS_WITH(solve_rte(slab(1.0, 1.0, 1.5, 0.1, 1.4, 10)), Catch::Contains("layer 1 g = 1.5 is outside [-1, 1]"));
    CHECK_THROWS_WITH(solve_rte(slab(1.0, 1.0, 0.0, 0.0, 1.4, 10)), Catch::Contains("thickness [cm] = 0 is outside (0, inf)"));
    auto r = slab(1.0, 1.0, 0.0, 0.1, 1.4, 10);
    r.incidence_deg = 90.0;
    CHECK_THROWS_AS(solve_rte(r), InputError);
}

TEST_CASE("white Monte Carlo reproduces the adding-doubling slabs too", "[rte_solver][replay]") {
    // The same independent reference as MCML's way: paths from mu_s, absorption by Beer-Lambert along them.
    for (const auto& ref : adding_doubling_slabs()) {
        RteRequest request;
        request.stack = ref.stack();
        request.photons = 200'000;
        request.white = true;
        const auto r = solve_rte(request);
        INFO("a " << ref.albedo << " b " << ref.optical_thickness << " g " << ref.g << " n " << ref.refractive_index);
        const double rd = ref.diffuse_reflectance, tt = ref.total_transmittance;
        CHECK(std::abs(r.diffuse_reflectance.value - rd) < 4.0 * r.diffuse_reflectance.stderr + 1e-3 * rd);
        CHECK(std::abs(r.transmittance.value - tt) < 4.0 * r.transmittance.stderr + 1e-3 * tt + 1e-12);
        CHECK(energy(r) == Approx(1.0).margin(1e-9));
    }
}

TEST_CASE("absorption replay: each replayed set equals its own white run, grids included", "[rte_solver][replay]") {
    auto request = slab(1.0, 100.0, 0.9, 0.1, 1.4, 4000);
    request.stack.layers.push_back({1.37, 0.5, 60.0, 0.05, PhaseFunction::henyey_greenstein(0.8)});
    request.grid = {0.01, 0.01, 20, 20, 6};
    request.seed = 5;
    const std::vector<std::vector<double>> sets{{0.1, 0.05}, {1.0, 0.5}, {20.0, 3.0}};
    const auto replayed = solve_rte_sets(request, sets);
    REQUIRE(replayed.size() == 3);
    for (std::size_t s = 0; s < sets.size(); ++s) {
        auto own = request;
        own.white = true;
        for (std::size_t k = 0; k < 2; ++k) own.stack.layers[k].mu_a_per_cm = sets[s][k];
        const auto direct = solve_rte(own);
        const auto& a = replayed[s];
        CHECK(a.diffuse_reflectance.value == Approx(direct.diffuse_reflectance.value).margin(1e-12));
        CHECK(a.diffuse_reflectance.stderr == Approx(direct.diffuse_reflectance.stderr).margin(1e-12));
        CHECK(a.transmittance.value == Approx(direct.transmittance.value).margin(1e-12));
        for (std::size_t k = 0; k < 2; ++k) CHECK(a.absorption_layers[k].value == Approx(direct.absorption_layers[k].value).margin(1e-12));
        for (std::size_t i = 0; i < a.absorption_rz.size(); ++i) CHECK(a.absorption_rz[i].value == Approx(direct.absorption_rz[i].value).margin(1e-9));
        for (std::size_t i = 0; i < a.reflectance_ra.size(); ++i) CHECK(a.reflectance_ra[i].value == Approx(direct.reflectance_ra[i].value).margin(1e-9));
        CHECK(energy(a) == Approx(1.0).margin(1e-9));  // per set
    }
    // More absorption, less light back: an ordering the sets must keep.
    CHECK(replayed[0].diffuse_reflectance.value > replayed[1].diffuse_reflectance.value);
    CHECK(replayed[1].diffuse_reflectance.value > replayed[2].diffuse_reflectance.value);
}

TEST_CASE("glass | absorber | glass with three indices: R and T of the incoherent multilayer in closed form", "[rte_solver]") {
    // No scattering: at normal incidence every photon stays on the axis, bouncing between the four interfaces. The
    // stack's R and T are the incoherent multiple-reflection sums (e.g. Born & Wolf; Heavens, Optical Properties of Thin
    // Solid Films, Sec. 4.8): two elements A then B combine as T = T_A T_B / (1 - R'_A R_B), R = R_A + T_A^2 R_B / (1 -
    // R'_A R_B), R' = R'_B + T_B^2 R'_A / (1 - R'_A R_B); an interface i|j reflects ((n_i - n_j) / (n_i + n_j))^2 both
    // ways, a layer transmits exp(-mu_a d). Every index differs, so a walk that took a neighbour's index at an internal
    // interface (above for below) misses these by far more than its standard errors.
    struct Element {
        double front, back, through;
    };
    const auto then = [](const Element& a, const Element& b) {
        const double d = 1.0 - a.back * b.front;
        return Element{a.front + a.through * a.through * b.front / d, b.back + b.through * b.through * a.back / d, a.through * b.through / d};
    };
    const auto interface = [](double ni, double nj) {
        const double r = (ni - nj) / (ni + nj);
        return Element{r * r, r * r, 1.0 - r * r};
    };
    const double n1 = 1.52, n2 = 1.33, n3 = 1.75, mu_a = 8.0, d = 0.05;  // absorber: exp(-0.4)
    RteRequest request;
    request.stack.layers.push_back({n1, 0.0, 0.0, 0.1, PhaseFunction::henyey_greenstein(0.0)});
    request.stack.layers.push_back({n2, mu_a, 0.0, d, PhaseFunction::henyey_greenstein(0.0)});
    request.stack.layers.push_back({n3, 0.0, 0.0, 0.2, PhaseFunction::henyey_greenstein(0.0)});
    request.photons = 100'000;
    request.seed = 17;
    Element stack = interface(1.0, n1);
    stack = then(stack, interface(n1, n2));
    stack = then(stack, Element{0.0, 0.0, std::exp(-mu_a * d)});
    stack = then(stack, interface(n2, n3));
    stack = then(stack, interface(n3, 1.0));
    const auto r = solve_rte(request);
    const double walk_r = r.specular_reflectance.value + r.diffuse_reflectance.value;
    INFO("R walk " << walk_r << " +- " << r.diffuse_reflectance.stderr << " closed form " << stack.front << "; T walk " << r.transmittance.value << " +- "
                   << r.transmittance.stderr << " closed form " << stack.through);
    CHECK(std::abs(walk_r - stack.front) < 4.0 * r.diffuse_reflectance.stderr + 1e-12);
    CHECK(std::abs(r.transmittance.value - stack.through) < 4.0 * r.transmittance.stderr + 1e-12);
    CHECK(energy(r) == Approx(1.0).margin(1e-9));
}

TEST_CASE("exit replay: every set's R and T agree with adding-doubling, its rings with its own walk", "[rte_solver][replay]") {
    // The six published slabs (independent reference for R and T) as absorption sets of one trace: the scattering and
    // geometry of each kept, mu_a x 1, x 0.3 and x 3 (the sets' floor is the x 0.3 one, so two sets are re-weighted).
    for (const auto& ref : adding_doubling_slabs()) {
        if (ref.albedo >= 1.0) continue;  // no absorption to vary
        for (const auto boundaries : {BoundaryMode::random, BoundaryMode::split}) {
            RteRequest request;
            request.stack = ref.stack();
            request.photons = 30'000;
            request.seed = 11;
            request.boundaries = boundaries;
            request.grid = {0.01, 0.05 / ref.stack().layers.front().mu_s_per_cm * 10.0, 0, 40, 0};
            request.within_radii_cm = {request.grid.dr_cm * 4.0, request.grid.dr_cm * 20.0};
            const double mu_a = ref.stack().layers.front().mu_a_per_cm;
            const std::vector<std::vector<double>> sets{{mu_a}, {0.3 * mu_a}, {3.0 * mu_a}};
            const auto replayed = solve_rte_exit_sets(request, sets);
            REQUIRE(replayed.size() == 3);
            INFO("a " << ref.albedo << " b " << ref.optical_thickness << " g " << ref.g << " boundaries " << to_string(boundaries));
            // Set 0 is the slab itself: adding-doubling's R and T.
            const auto& r0 = replayed.front();
            CHECK(std::abs(r0.diffuse_reflectance.value - ref.diffuse_reflectance) < 4.0 * r0.diffuse_reflectance.stderr + 1e-3 * ref.diffuse_reflectance);
            CHECK(std::abs(r0.transmittance.value - ref.total_transmittance) < 4.0 * r0.transmittance.stderr + 1e-3 * ref.total_transmittance + 1e-12);
            for (std::size_t s = 0; s < sets.size(); ++s) {
                auto own = request;
                own.seed = 23;  // independent photons
                own.stack.layers.front().mu_a_per_cm = sets[s][0];
                const auto direct = solve_rte(own);
                const auto& a = replayed[s];
                INFO("set " << s);
                const auto close = [](const Estimate& x, const Estimate& y) { return std::abs(x.value - y.value) <= 4.0 * std::hypot(x.stderr, y.stderr) + 1e-12; };
                CHECK(close(a.diffuse_reflectance, direct.diffuse_reflectance));
                CHECK(close(a.transmittance, direct.transmittance));
                REQUIRE(a.reflectance_within.size() == 2);
                for (std::size_t k = 0; k < 2; ++k) CHECK(close(a.reflectance_within[k], direct.reflectance_within[k]));
                // Rings: chi-square per ring of the two independent estimates (standard errors per photon here, batch
                // means there) near 1, and no ring beyond 5 sigma.
                double chi2 = 0.0;
                std::size_t rings = 0;
                REQUIRE(a.reflectance_r.size() == direct.reflectance_r.size());
                for (std::size_t i = 0; i + 1 < a.reflectance_r.size(); ++i) {
                    const double v = std::hypot(a.reflectance_r[i].stderr, direct.reflectance_r[i].stderr);
                    if (!(v > 0.0)) continue;
                    const double z = (a.reflectance_r[i].value - direct.reflectance_r[i].value) / v;
                    CHECK(std::abs(z) < 5.0);
                    chi2 += z * z;
                    ++rings;
                }
                CHECK(chi2 / static_cast<double>(std::max<std::size_t>(1, rings)) < 2.0);
            }
            // More absorption, less light back.
            CHECK(replayed[1].diffuse_reflectance.value > replayed[0].diffuse_reflectance.value);
            CHECK(replayed[0].diffuse_reflectance.value > replayed[2].diffuse_reflectance.value);
        }
    }
}

TEST_CASE("exit replay: the set at the floor is the floor's own white walk, exit for exit", "[rte_solver][replay]") {
    // The same paths, roulette and exits: the floor set's escapes equal those of a white run with its absorption, to the
    // float precision of the recorded paths.
    auto request = slab(1.0, 100.0, 0.9, 0.1, 1.4, 20'000);
    request.stack.layers.push_back({1.37, 0.5, 60.0, 0.05, PhaseFunction::henyey_greenstein(0.8)});
    request.grid = {0.01, 0.01, 0, 20, 0};
    request.within_radii_cm = {0.02, 0.1};
    request.seed = 5;
    const auto replayed = solve_rte_exit_sets(request, {{1.0, 0.5}, {4.0, 2.0}});
    auto own = request;
    own.white = true;
    const auto direct = solve_rte(own);
    const auto& a = replayed.front();
    CHECK(a.photons == direct.photons);
    CHECK(a.diffuse_reflectance.value == Approx(direct.diffuse_reflectance.value).epsilon(1e-5));
    CHECK(a.transmittance.value == Approx(direct.transmittance.value).epsilon(1e-5));
    for (std::size_t k = 0; k < 2; ++k) CHECK(a.reflectance_within[k].value == Approx(direct.reflectance_within[k].value).epsilon(1e-5));
    for (std::size_t i = 0; i < a.reflectance_r.size(); ++i) CHECK(a.reflectance_r[i].value == Approx(direct.reflectance_r[i].value).epsilon(1e-5));
    // The same numbers on one thread (batches merged in order, exits replayed in batch order).
    {
        const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        const auto alone = solve_rte_exit_sets(request, {{1.0, 0.5}, {4.0, 2.0}});
        for (std::size_t s = 0; s < 2; ++s) {
            CHECK(alone[s].diffuse_reflectance.value == replayed[s].diffuse_reflectance.value);
            CHECK(alone[s].diffuse_reflectance.stderr == replayed[s].diffuse_reflectance.stderr);
            for (std::size_t i = 0; i < a.reflectance_r.size(); ++i) CHECK(alone[s].reflectance_r[i].value == replayed[s].reflectance_r[i].value);
        }
    }
    CHECK_THROWS_WITH(solve_rte_exit_sets(request, {}), Catch::Contains("no absorption sets"));
    request.grid.nz = 5;
    CHECK_THROWS_WITH(solve_rte_exit_sets(request, {{1.0, 0.5}}), Catch::Contains("only escapes are tallied"));
}

TEST_CASE("a band material is walked as its semi-infinite medium: R per band agrees with adding-doubling, nothing leaves below", "[rte_solver]") {
    for (const auto* preset : {"jensen2001-skin1", "jensen2001-marble"}) {
        CAPTURE(preset);
        const auto material = std::get<HomogeneousMaterial>(load_material(preset));
        SpectralRequest request;
        request.stderr_target = 0.002;
        request.seed = 5;
        const auto result = solve_rte_bands(material, request);
        REQUIRE(result.wavelengths.size() == material.bands.size());
        CHECK(result.bands == material.bands);
        CHECK(result.warnings.empty());
        for (std::size_t b = 0; b < material.bands.size(); ++b) {
            CAPTURE(material.bands[b]);
            const auto& w = result.wavelengths[b];
            // The independent solver (adding-doubling, checked against Prahl's tables) on the same slab.
            const auto reference = solve_adding_doubling(rte_band_slab(material, b), {});
            const double r_reference = reference.specular_reflectance + reference.diffuse_reflectance;
            CHECK(std::abs(w.reflectance.value - r_reference) <= 4.0 * w.reflectance.stderr + reference.accuracy);
            CHECK(w.transmittance.value < 1e-9);
            double absorbed = 0.0;
            for (const auto& a : w.absorptance_layers) absorbed += a.value;
            CHECK(w.reflectance.value + w.transmittance.value + absorbed == Approx(1.0).margin(1e-12));  // energy conservation
        }
    }
}
