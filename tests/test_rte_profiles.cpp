#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "materials/material_file.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"
#include "transport/rte/rte_profiles.hpp"

using namespace skinspec;

namespace {

std::vector<double> radii(std::size_t n, double step) {
    std::vector<double> r;
    for (std::size_t i = 0; i < n; ++i) r.push_back(static_cast<double>(i) * step);
    return r;
}

}  // namespace

TEST_CASE("the walk's R(r) rings add up to its whole-plane diffuse reflectance", "[rte_profiles]") {
    // Energy conservation of the tally: sum_i R(r_i) * area of the ring centred on r_i (disc of radius h/2 at 0)
    // over radii far beyond the light's reach equals the diffuse R counted photon by photon.
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const double h = 0.05;
    const auto r = radii(401, h);  // 0-20 mm
    const auto p = solve_rte_profiles(stack, WavelengthGrid::list({650.0}), r, true, RteProfileOptions{100'000, std::nullopt, 3});
    REQUIRE(p.channels.size() == 1);
    const auto& c = p.channels.front();
    double sum = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const double area = i == 0 ? std::numbers::pi * 0.25 * h * h : 2.0 * std::numbers::pi * r[i] * h;
        sum += area * c.reflectance_per_mm2[i];
        variance += area * area * c.reflectance_stderr_per_mm2[i] * c.reflectance_stderr_per_mm2[i];
        CHECK(c.reflectance_stderr_per_mm2[i] >= 0.0);
    }
    CHECK(std::abs(sum - c.total_reflectance) < 4.0 * std::sqrt(variance) + 1e-4);
    CHECK(c.transmittance_per_mm2.size() == r.size());
    // Monotone decrease well away from the source, as every diffusing medium's.
    CHECK(c.reflectance_per_mm2[20] > c.reflectance_per_mm2[40]);
    CHECK(c.reflectance_per_mm2[40] > c.reflectance_per_mm2[80]);
}

TEST_CASE("the walk's profiles need rings, deterministic solvers refuse ray counts", "[rte_profiles]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto grid = WavelengthGrid::list({550.0});
    CHECK_THROWS_WITH(solve_rte_profiles(stack, grid, std::vector<double>{0.1, 0.2, 0.3}, false, {}), Catch::Contains("must start at 0 mm with equal steps"));
    CHECK_THROWS_WITH(solve_rte_profiles(stack, grid, std::vector<double>{0.0, 0.1, 0.3}, false, {}), Catch::Contains("radius 0.3 mm is not 2 x 0.1 mm"));
    CHECK_THROWS_WITH(solve_rte_profiles(stack, grid, std::vector<double>{0.0}, false, {}), Catch::Contains("at least two radii"));
    ProfileRequest request{grid, {0.0, 0.5, 1.0}, false, {}, std::uint64_t{1000}};
    CHECK_THROWS_WITH(solve_profiles(find_solver("multipole"), Material(stack), request), Catch::Contains("'multipole' is deterministic: it takes no ray count"));
    CHECK(solve_profiles(find_solver("rte"), Material(stack), request).channels.front().reflectance_stderr_per_mm2.size() == 3);
}

TEST_CASE("the radii a precision target covers: a 1-2-5 series from the step to the reach", "[rte_profiles]") {
    const auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
        return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) { return std::abs(x - y) <= 1e-12 * y; });
    };
    CHECK(same(within_radii_mm(radii(1001, 0.01)), {0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 10.005}));
    CHECK(same(within_radii_mm(radii(3, 0.3)), {0.5, 0.75}));
    CHECK(within_radii_mm(std::vector<double>{0.0}).empty());
}

TEST_CASE("an exact profile runs until the reflectance within every radius meets its standard-error target", "[rte_profiles]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto r = radii(401, 0.025);  // 0-10 mm
    RteProfileOptions options;
    options.stderr_target = 0.004;
    const auto a = solve_rte_profiles(stack, WavelengthGrid::list({550.0}), r, false, options);
    const auto& c = a.channels.front();
    CHECK(c.converged);
    CHECK(c.within_radius_stderr <= 0.004);
    CHECK(c.within_radius_stderr > 0.5 * 0.004);  // the walk stops near its target, not far beyond it
    CHECK(c.rays < 200'000);
    REQUIRE(a.stderr_target);
    // The standard errors are honest: the reflectance within each radius of two independent runs (other seeds) agrees
    // within 4 combined standard errors, as photon-by-photon tallies of the same quantity.
    RteRequest request;
    request.stack = rte_stack_from(stack, 550.0);
    request.photons = 20'000;
    request.within_radii_cm = {0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5};
    request.seed = 11;
    const auto first = solve_rte(request);
    request.seed = 12;
    const auto second = solve_rte(request);
    for (std::size_t k = 0; k < request.within_radii_cm.size(); ++k) {
        const auto& x = first.reflectance_within[k];
        const auto& y = second.reflectance_within[k];
        INFO("within " << request.within_radii_cm[k] << " cm");
        CHECK(std::abs(x.value - y.value) < 4.0 * std::hypot(x.stderr, y.stderr));
        if (k > 0) CHECK(x.value >= first.reflectance_within[k - 1].value);
    }
    // Beyond the light's reach the enclosed reflectance is the whole-plane diffuse reflectance, photon for photon.
    request.within_radii_cm = {100.0};
    const auto whole = solve_rte(request);
    CHECK(whole.reflectance_within.front().value == Approx(whole.diffuse_reflectance.value).epsilon(1e-12));
    // Refused: radii that do not increase.
    request.within_radii_cm = {0.1, 0.1};
    CHECK_THROWS_WITH(solve_rte(request), Catch::Contains("within radii: 0.1 cm is not positive and above the one before"));
}

TEST_CASE("profiles default to the exact transport, band materials walked as semi-infinite media", "[rte_profiles]") {
    CHECK(default_profile_solver().name() == "rte");
    // A band material's profile by the walk: its total diffuse R against adding-doubling of the same slab (an independent
    // method) within 4 standard errors and the quadrature's stated accuracy.
    const auto skin1 = std::get<HomogeneousMaterial>(load_material("jensen2001-skin1"));
    ProfileRequest request;
    request.radii_mm = radii(201, 0.1);
    request.stderr_target = 0.004;
    const auto p = solve_profiles(default_profile_solver(), Material(skin1), request);
    REQUIRE(p.channels.size() == skin1.bands.size());
    for (std::size_t b = 0; b < skin1.bands.size(); ++b) {
        const auto exact = solve_adding_doubling(rte_band_slab(skin1, b), {});
        const auto& c = p.channels[b];
        INFO("band " << c.label);
        CHECK(c.label == skin1.bands[b]);
        CHECK(c.converged);
        CHECK(std::abs(c.total_reflectance - exact.diffuse_reflectance) < 4.0 * c.within_radius_stderr + exact.accuracy);
    }
}

TEST_CASE("a pigmentation grid's profiles from one walk agree with each member's own walk", "[rte_profiles][replay]") {
    // The layers' own volumetric description: melanin and blood change absorption only, so one walk serves them all
    // (the exit replay); each member's own walk (MCML's way, other photons) is the independent estimate.
    const auto base = load_material("biospec-moderately", {parse_override("model.volumetric_matched_to_biospec=false")});
    std::vector<Material> members;
    for (const char* melanin : {"0.01", "0.2"}) {
        for (const char* blood : {"0.002", "0.05"}) {
            members.push_back(with_overrides(base, {parse_override(std::string("epidermis.melanosome_fraction=") + melanin),
                                                    parse_override(std::string("papillary_dermis.blood_fraction=") + blood)}));
        }
    }
    std::vector<const LayerStack*> stacks;
    for (const auto& m : members) stacks.push_back(&std::get<LayerStack>(m));
    const auto r = radii(41, 0.05);  // 0-2 mm
    const auto grid = WavelengthGrid::list({450.0, 650.0});
    const auto together = solve_rte_profiles(stacks, grid, r, false, RteProfileOptions{40'000, std::nullopt, 7});
    REQUIRE(together.size() == members.size());
    for (std::size_t m = 0; m < members.size(); ++m) {
        const auto own = solve_rte_profiles(*stacks[m], grid, r, false, RteProfileOptions{40'000, std::nullopt, 9});
        for (std::size_t c = 0; c < grid.size(); ++c) {
            const auto& a = together[m].channels[c];
            const auto& b = own.channels[c];
            INFO("member " << m << " channel " << a.label);
            CHECK(a.rays == 40'000);
            double chi2 = 0.0;
            std::size_t n = 0;
            for (std::size_t i = 0; i < r.size(); ++i) {
                const double v = std::hypot(a.reflectance_stderr_per_mm2[i], b.reflectance_stderr_per_mm2[i]);
                if (!(v > 0.0)) continue;
                const double z = (a.reflectance_per_mm2[i] - b.reflectance_per_mm2[i]) / v;
                CHECK(std::abs(z) < 5.0);
                chi2 += z * z;
                ++n;
            }
            CHECK(chi2 / static_cast<double>(std::max<std::size_t>(1, n)) < 2.0);
        }
    }
    // Melanin and blood take light away: the lightest member reflects the most at every wavelength.
    for (std::size_t c = 0; c < grid.size(); ++c) {
        for (std::size_t m = 1; m < members.size(); ++m) CHECK(together[0].channels[c].total_reflectance > together[m].channels[c].total_reflectance);
    }
}

TEST_CASE("a grid whose members scatter differently is walked member by member", "[rte_profiles][replay]") {
    // The description derived from the BioSpec one scales the dermis's mu_s with the absorbers (matched_volumetric.hpp):
    // its members share no paths, and the exit replay refuses them.
    const auto a = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto b = std::get<LayerStack>(load_material("biospec-moderately", {parse_override("epidermis.melanosome_fraction=0.3")}));
    CHECK_THROWS_WITH(solve_rte_profiles({&a, &b}, WavelengthGrid::list({550.0}), radii(5, 0.1), false, RteProfileOptions{1000, std::nullopt, 1}),
                      Catch::Contains("paths"));
    const std::vector<Material> owned{a, b};
    const std::vector<const Material*> materials{&owned[0], &owned[1]};
    ProfileRequest request{WavelengthGrid::list({550.0}), radii(5, 0.1), false, {}, std::uint64_t{2000}};
    const auto p = solve_profiles(find_solver("rte"), materials, request);
    REQUIRE(p.size() == 2);
    CHECK(p[0].channels.front().total_reflectance > p[1].channels.front().total_reflectance);
}
