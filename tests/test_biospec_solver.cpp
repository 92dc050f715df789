#include <catch2/catch.hpp>

#include <cmath>

#include <tbb/global_control.h>

#include "transport/biospec/biospec_solver.hpp"
#include "transport/fresnel.hpp"
#include "materials/measured_profile.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "energy_balance.hpp"

using namespace skinspec;
using skinspec::testing::energy;

namespace {

LayerStack preset(const char* name) { return std::get<LayerStack>(load_material(name)); }

SpectralRequest all_quantities(std::vector<double> nm, std::uint64_t rays) {
    SpectralRequest r;
    r.wavelengths = WavelengthGrid::list(std::move(nm));
    r.quantities = Quantities{true, true, true, false};
    r.max_rays_per_wavelength = rays;
    return r;
}

void check_physical(const SpectralResult& result) {
    for (const auto& w : result.wavelengths) {
        INFO(w.wavelength_nm << " nm");
        for (const double v : {w.reflectance.value, w.transmittance.value, w.specular_reflectance.value}) {
            CHECK(std::isfinite(v));
            CHECK(v >= 0.0);
            CHECK(v <= 1.0);
        }
        for (const auto& a : w.absorptance_layers) {
            CHECK(std::isfinite(a.value));
            CHECK(a.value >= -1e-12);
        }
        CHECK(energy(w) == Approx(1.0).margin(1e-12));
    }
}

}  // namespace

TEST_CASE("energy is conserved to rounding with the weighted estimator", "[biospec_solver]") {
    for (const char* name : {"biospec-lightly", "biospec-very-heavily"}) {
        for (const char* bottom : {"diffuse_reflector", "exit"}) {
            INFO(name << ", " << bottom);
            const auto stack = std::get<LayerStack>(load_material(name, {{"bottom.boundary", bottom}}));
            check_physical(solve_biospec(stack, all_quantities({400, 480, 542, 576, 650, 700}, 20'000)));
        }
    }
}

TEST_CASE("the same seed gives identical numbers on 1 and 2 threads", "[biospec_solver]") {
    const auto stack = preset("biospec-moderately");
    auto request = all_quantities({450, 550, 650}, 0);
    request.stderr_target = 0.004;
    request.max_rays_per_wavelength = 1'000'000;
    const auto run = [&](int threads) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
        return solve_biospec(stack, request);
    };
    const auto one = run(1);
    const auto two = run(2);
    REQUIRE(one.wavelengths.size() == two.wavelengths.size());
    for (std::size_t i = 0; i < one.wavelengths.size(); ++i) {
        CHECK(one.wavelengths[i].rays == two.wavelengths[i].rays);
        CHECK(one.wavelengths[i].reflectance.value == two.wavelengths[i].reflectance.value);
        CHECK(one.wavelengths[i].reflectance.stderr == two.wavelengths[i].reflectance.stderr);
        CHECK(one.wavelengths[i].absorptance_layers[1].value == two.wavelengths[i].absorptance_layers[1].value);
    }
}

TEST_CASE("the SC alone reproduces the measured cumulative profile it was built from", "[biospec_solver]") {
    // Stratum corneum only, no absorbers, index-matched (n = 1 everywhere), reflector off, normal incidence:
    // every ray crosses once and leaves with the measured deflection. 1e6 rays; within 1 % at every angle. 491 nm
    // lies between two tabulated profiles: the walk samples it as their mixture.
    auto stack = preset("biospec-lightly");
    stack.layers.resize(1);
    stack.layers[0].carotene_g_per_l = 0.0;
    stack.layers[0].refractive_index = 1.0;
    stack.model.baseline_absorption = false;
    stack.bottom = BottomBoundary::exit;
    const auto& profile = MeasuredProfile::stratum_corneum();
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({436.0, 491.0, 546.0});
    request.quantities = Quantities{true, true, false, true};
    request.max_rays_per_wavelength = 1'000'000;
    const auto result = solve_biospec(stack, request);
    for (const auto& w : result.wavelengths) {
        INFO(w.wavelength_nm << " nm");
        CHECK(w.transmittance.value == Approx(1.0).margin(1e-12));
        CHECK(w.reflectance.value == 0.0);
        // Goniometer bins 0-2.5, 2.5-7.5, ...: back from BTDF to the fraction per bin, then cumulate.
        const auto& edges = result.angular_bin_edges_deg;
        const auto measured = profile.cumulative(w.wavelength_nm);
        double cumulative = 0.0;
        for (std::size_t b = 0; b + 1 < edges.size() && edges[b + 1] <= 62.5; ++b) {
            const double deg = std::numbers::pi / 180.0;
            const double solid_angle = 2.0 * std::numbers::pi * (std::cos(edges[b] * deg) - std::cos(edges[b + 1] * deg));
            cumulative += w.btdf_per_sr[b].value * solid_angle * std::cos(0.5 * (edges[b] + edges[b + 1]) * deg);
            INFO("up to " << edges[b + 1] << " deg");
            CHECK(cumulative == Approx(measured[b + 1]).epsilon(0.01));
        }
    }
}

TEST_CASE("the random and weighted absorption estimators agree within statistical error", "[biospec_solver]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately", {{"bottom.boundary", "exit"}}));
    const auto request = all_quantities({420, 560, 680}, 200'000);
    BiospecOptions random;
    random.estimator = AbsorptionEstimator::random_test;
    const auto a = solve_biospec(stack, request);
    const auto b = solve_biospec(stack, request, random);
    for (std::size_t i = 0; i < a.wavelengths.size(); ++i) {
        const auto& x = a.wavelengths[i];
        const auto& y = b.wavelengths[i];
        INFO(x.wavelength_nm << " nm");
        const auto agree = [](const Estimate& p, const Estimate& q) {
            return std::abs(p.value - q.value) < 4.0 * std::hypot(p.stderr, q.stderr) + 1e-12;
        };
        CHECK(agree(x.reflectance, y.reflectance));
        CHECK(agree(x.transmittance, y.transmittance));
        for (std::size_t k = 0; k < x.absorptance_layers.size(); ++k) CHECK(agree(x.absorptance_layers[k], y.absorptance_layers[k]));
        // The weighted estimator has the lower variance for absorption.
        CHECK(x.absorptance_layers[1].stderr < y.absorptance_layers[1].stderr);
        CHECK(energy(y) == Approx(1.0).margin(1e-12));
    }
}

TEST_CASE("without absorbers and reflector all light leaves", "[biospec_solver]") {
    auto stack = std::get<LayerStack>(load_material("biospec-lightly", {{"bottom.boundary", "exit"}}));
    for (auto& l : stack.layers) {
        l.melanosome_fraction = 0.0;
        l.blood_fraction = 0.0;
        l.carotene_g_per_l = 0.0;
        l.water_fraction = 0.0;
    }
    stack.model.baseline_absorption = false;
    const auto result = solve_biospec(stack, all_quantities({450, 600}, 20'000));
    for (const auto& w : result.wavelengths) CHECK(w.reflectance.value + w.transmittance.value == Approx(1.0).margin(1e-12));
}

TEST_CASE("more melanin lowers R at every wavelength, more blood deepens the haemoglobin dips", "[biospec_solver]") {
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::range(400.0, 700.0, 20.0);
    request.max_rays_per_wavelength = 100'000;
    const auto light = solve_biospec(preset("biospec-lightly"), request);
    const auto heavy = solve_biospec(preset("biospec-heavily"), request);
    for (std::size_t i = 0; i < light.wavelengths.size(); ++i) {
        const auto& a = light.wavelengths[i].reflectance;
        const auto& b = heavy.wavelengths[i].reflectance;
        INFO(light.wavelengths[i].wavelength_nm << " nm");
        CHECK(b.value < a.value - 3.0 * std::hypot(a.stderr, b.stderr));
    }
    SpectralRequest dips;
    dips.wavelengths = WavelengthGrid::list({420.0, 542.0, 576.0, 680.0});
    dips.max_rays_per_wavelength = 200'000;
    const auto normal = solve_biospec(preset("biospec-lightly"), dips);
    const auto more_blood = solve_biospec(
        std::get<LayerStack>(load_material("biospec-lightly", {parse_override("dermis.blood_fraction=0.04")})), dips);
    const auto drop = [&](std::size_t i) { return 1.0 - more_blood.wavelengths[i].reflectance.value / normal.wavelengths[i].reflectance.value; };
    for (std::size_t i = 0; i < 3; ++i) {
        INFO(dips.wavelengths[i] << " nm");
        CHECK(drop(i) > 0.05);
        CHECK(drop(i) > 2.0 * drop(3));  // the dips deepen more than the red where blood absorbs little
    }
}

TEST_CASE("the published shape of skin reflectance", "[biospec_solver]") {
    // Low in the blue, rising steeply above 600 nm; 0.45-0.7 at 700 nm for lightly pigmented skin
    // (the model's published curves, Krishnaswamy & Baranoski 2004; the corrected model sits at the low end).
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({450.0, 560.0, 576.0, 600.0, 700.0});
    request.max_rays_per_wavelength = 100'000;
    const auto r = solve_biospec(preset("biospec-lightly"), request).wavelengths;
    CHECK(r[0].reflectance.value < r[4].reflectance.value / 2.0);
    CHECK(r[2].reflectance.value < r[1].reflectance.value);
    CHECK(r[4].reflectance.value > r[3].reflectance.value + 0.05);
    CHECK(r[4].reflectance.value > 0.45);
    CHECK(r[4].reflectance.value < 0.7);
}

TEST_CASE("one set without the absorptance carries its depth whole: the same rays as with paths per layer", "[biospec_solver]") {
    // R and T only: the packet keeps the set's optical depth (no path per layer); with the absorptance it keeps the
    // paths and forms the depth from them. The same rays, so equal up to the rounding of the two sums.
    for (const char* bottom : {"diffuse_reflector", "exit"}) {
        INFO(bottom);
        const auto stack = std::get<LayerStack>(load_material("biospec-heavily", {{"bottom.boundary", bottom}}));
        auto with_paths = all_quantities({420, 550, 650}, 40'000);
        auto depth_only = with_paths;
        depth_only.quantities = Quantities{true, true, false, false};
        const auto a = solve_biospec(stack, with_paths), b = solve_biospec(stack, depth_only);
        for (std::size_t i = 0; i < a.wavelengths.size(); ++i) {
            INFO(a.wavelengths[i].wavelength_nm << " nm");
            CHECK(b.wavelengths[i].reflectance.value == Approx(a.wavelengths[i].reflectance.value).epsilon(1e-5));
            CHECK(b.wavelengths[i].transmittance.value == Approx(a.wavelengths[i].transmittance.value).epsilon(1e-5).margin(1e-9));
        }
    }
    // A mu_a beyond single precision keeps the paths per layer (a depth of inf * 0 would be NaN): the surface's light only.
    const auto dark = std::get<LayerStack>(load_material("biospec-moderately", {{"epidermis.eumelanin_mg_per_ml", "1e40"}}));
    auto request = all_quantities({550}, 20'000);
    request.quantities = Quantities{true, false, false, false};
    const double r = solve_biospec(dark, request).wavelengths[0].reflectance.value;
    CHECK(std::isfinite(r));
    CHECK(r > 0.03);
    CHECK(r < 0.06);
}

TEST_CASE("extreme inputs finish with finite results in [0, 1] and conserved energy", "[biospec_solver]") {
    struct Case { const char* what; std::vector<MaterialOverride> overrides; double incidence; std::vector<double> nm; };
    const std::vector<Case> cases{
        {"thin layers", {{"epidermis.thickness_cm", "1e-9"}, {"dermis.thickness_cm", "1e-9"}, {"stratum_corneum.thickness_cm", "1e-9"}}, 0.0, {550}},
        {"thick layers", {{"epidermis.thickness_cm", "1e3"}, {"dermis.thickness_cm", "1e3"}}, 0.0, {550}},
        {"fractions 0", {{"epidermis.melanosome_fraction", "0"}, {"dermis.blood_fraction", "0"}}, 0.0, {550}},
        {"melanosomes 1", {{"epidermis.melanosome_fraction", "1"}}, 0.0, {550}},
        {"blood 1", {{"dermis.blood_fraction", "1"}, {"dermis.oxygen_saturation", "1"}}, 0.0, {550}},
        {"fold near 0", {{"surface.fold_aspect_ratio", "1e-6"}}, 60.0, {550}},
        {"fold 1", {{"surface.fold_aspect_ratio", "1"}}, 60.0, {550}},
        {"grazing incidence", {}, 89.9, {550}},
        {"table edges", {}, 0.0, {250.0, 820.0}},
        {"reflector off, grazing", {{"bottom.boundary", "exit"}}, 89.9, {400}},
        {"resample folds", {}, 80.0, {550}},
    };
    for (const auto& c : cases) {
        INFO(c.what);
        const auto stack = std::get<LayerStack>(load_material("biospec-moderately", c.overrides));
        auto request = all_quantities(c.nm, 20'000);
        request.incidence_deg = c.incidence;
        BiospecOptions options;
        if (std::string(c.what) == "resample folds") options.fold_into_skin = FoldIntoSkin::resample;
        const auto result = solve_biospec(stack, request, options);
        check_physical(result);
        if (std::string(c.what) == "resample folds") CHECK(result.wavelengths[0].absorptance_surface.value == 0.0);
    }
    // At 80 deg the 2004 behaviour drops fold reflections pointing into the skin.
    auto request = all_quantities({550}, 20'000);
    request.incidence_deg = 80.0;
    CHECK(solve_biospec(preset("biospec-moderately"), request).wavelengths[0].absorptance_surface.value > 0.0);
}

TEST_CASE("the event limit stops rays with a documented outcome", "[biospec_solver]") {
    BiospecOptions options;
    options.max_events_per_ray = 3;
    const auto result = solve_biospec(preset("biospec-lightly"), all_quantities({650}, 10'000), options);
    CHECK(result.wavelengths[0].truncated_rays > 0);
    check_physical(result);
}

TEST_CASE("bad requests are input errors naming the value and range", "[biospec_solver]") {
    const auto stack = preset("biospec-lightly");
    auto request = all_quantities({550}, 100);
    request.incidence_deg = 90.0;
    CHECK_THROWS_WITH(solve_biospec(stack, request), "incidence angle 90 deg is outside [0, 90)");
    request.incidence_deg = 0.0;
    request.stderr_target = 0.0;
    CHECK_THROWS_WITH(solve_biospec(stack, request), "standard error target 0 is outside (0, inf)");
    request.stderr_target.reset();
    request.wavelengths = WavelengthGrid::list({2600.0});
    CHECK_THROWS_WITH(solve_biospec(stack, request), Catch::Contains("baseline tissue: wavelength 2600 nm is outside"));
    request.wavelengths = WavelengthGrid::list({550.0});
    BiospecOptions options;
    options.max_events_per_ray = 3'000'000'000u;  // the packets count events in 32-bit signed lanes
    CHECK_THROWS_WITH(solve_biospec(stack, request, options), "maximum events per ray 3000000000 is outside [1, 2147483647]");
}

namespace {

std::vector<LayerStack> melanin_levels(const std::vector<double>& fractions) {
    std::vector<LayerStack> stacks;
    for (const double f : fractions) {
        auto s = std::get<LayerStack>(load_material("biospec-moderately", {{"epidermis.melanosome_fraction", std::to_string(f)}}));
        s.name = "v_m " + std::to_string(f);
        stacks.push_back(std::move(s));
    }
    return stacks;
}

// The sets solve_biospec_sets takes: one pointer per stack.
std::vector<const LayerStack*> pointers_to(const std::vector<LayerStack>& stacks) {
    std::vector<const LayerStack*> sets;
    for (const auto& s : stacks) sets.push_back(&s);
    return sets;
}

}  // namespace

TEST_CASE("absorption replay: each replayed level equals its own run with the same rays and seed", "[biospec_solver][replay]") {
    auto stacks = melanin_levels({0.005, 0.05, 0.25});
    stacks[1].layers[2].blood_fraction = 0.03;          // blood and oxygenation replay too
    stacks[2].layers[3].oxygen_saturation = 0.4;
    const auto sets = pointers_to(stacks);
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({420.0, 550.0, 650.0});
    request.quantities = {true, true, true, true};
    request.max_rays_per_wavelength = 3000;
    request.seed = 11;
    const auto replayed = solve_biospec_sets(sets, request);
    REQUIRE(replayed.size() == 3);
    for (std::size_t s = 0; s < stacks.size(); ++s) {
        const auto direct = solve_biospec(stacks[s], request);
        for (std::size_t w = 0; w < direct.wavelengths.size(); ++w) {
            const auto& a = replayed[s].wavelengths[w];
            const auto& b = direct.wavelengths[w];
            CHECK(a.reflectance.value == Approx(b.reflectance.value).margin(1e-12));
            CHECK(a.reflectance.stderr == Approx(b.reflectance.stderr).margin(1e-12));
            CHECK(a.transmittance.value == Approx(b.transmittance.value).margin(1e-12));
            for (std::size_t k = 0; k < a.absorptance_layers.size(); ++k) {
                CHECK(a.absorptance_layers[k].value == Approx(b.absorptance_layers[k].value).margin(1e-12));
            }
            for (std::size_t i = 0; i < a.brdf_per_sr.size(); ++i) CHECK(a.brdf_per_sr[i].value == Approx(b.brdf_per_sr[i].value).margin(1e-12));
            CHECK(a.truncated_rays == b.truncated_rays);
            // Energy per set: R + T + A (every layer and the surface) = 1 (conservation).
            double sum = a.reflectance.value + a.transmittance.value + a.absorptance_surface.value;
            for (const auto& x : a.absorptance_layers) sum += x.value;
            CHECK(sum == Approx(1.0).margin(1e-9));
        }
    }
}

TEST_CASE("absorption replay agrees with independent runs (another seed) within 4 combined sigma", "[biospec_solver][replay]") {
    const auto stacks = melanin_levels({0.01, 0.08, 0.3});
    const auto sets = pointers_to(stacks);
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({450.0, 600.0});
    request.stderr_target = 0.003;
    request.max_rays_per_wavelength = 2'000'000;
    const auto replayed = solve_biospec_sets(sets, request);
    auto other = request;
    other.seed = 777;
    for (std::size_t s = 0; s < stacks.size(); ++s) {
        const auto direct = solve_biospec(stacks[s], other);
        for (std::size_t w = 0; w < direct.wavelengths.size(); ++w) {
            const auto& a = replayed[s].wavelengths[w].reflectance;
            const auto& b = direct.wavelengths[w].reflectance;
            CHECK(a.stderr <= 0.003);  // every set meets the target
            CHECK(std::abs(a.value - b.value) <= 4.0 * std::hypot(a.stderr, b.stderr));
        }
        // R alone: the sets re-weight recorded paths (solve_biospec_sets) and say so.
        CHECK(std::get<std::string>(replayed[s].settings.at("absorption_sets_estimator")).starts_with("recorded paths"));
    }
}

TEST_CASE("recorded paths re-weighted per set: identical on 1 and 2 threads, specular and truncated rays counted", "[biospec_solver][replay]") {
    const auto stacks = melanin_levels({0.005, 0.05, 0.25});
    const auto sets = pointers_to(stacks);
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({420.0, 650.0});
    request.stderr_target = 0.004;
    request.max_rays_per_wavelength = 1'000'000;
    const auto run = [&](int threads, const SpectralRequest& r) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
        return solve_biospec_sets(sets, r);
    };
    const auto one = run(1, request), two = run(2, request);
    auto other = request;
    other.seed = 5;
    const auto own = solve_biospec(stacks[0], other);  // the weighted walk's own tally of the first-surface reflection
    for (std::size_t s = 0; s < sets.size(); ++s) {
        for (std::size_t w = 0; w < 2; ++w) {
            const auto& a = one[s].wavelengths[w];
            const auto& b = two[s].wavelengths[w];
            CHECK(a.rays == b.rays);
            CHECK(a.reflectance.value == b.reflectance.value);
            CHECK(a.reflectance.stderr == b.reflectance.stderr);
            CHECK(a.reflectance.stderr <= 0.004);
            // The first-surface reflection does not depend on the absorbers: every set has the same, and the walk's own
            // run (another seed) agrees within 4 combined standard errors.
            CHECK(a.specular_reflectance.value == one[0].wavelengths[w].specular_reflectance.value);
            const auto& mine = own.wavelengths[w].specular_reflectance;
            CHECK(std::abs(a.specular_reflectance.value - mine.value) <= 4.0 * std::hypot(a.specular_reflectance.stderr, mine.stderr));
            CHECK(a.truncated_rays == 0);
        }
    }
    // A ray stopped at the event limit is counted for every set (here every ray that enters the skin).
    auto few = request;
    few.stderr_target.reset();
    few.max_rays_per_wavelength = 2000;
    BiospecOptions limited;
    limited.max_events_per_ray = 1;
    const auto stopped = solve_biospec_sets(sets, few, limited);
    for (const auto& result : stopped) CHECK(result.wavelengths.front().truncated_rays > 1000);
}

TEST_CASE("absorption replay refuses sets whose paths differ and the random estimator", "[biospec_solver][replay]") {
    auto stacks = melanin_levels({0.01, 0.05});
    stacks[1].layers[1].thickness_cm *= 2.0;
    const std::vector<const LayerStack*> sets{&stacks[0], &stacks[1]};
    SpectralRequest request;
    request.max_rays_per_wavelength = 100;
    CHECK_THROWS_WITH(solve_biospec_sets(sets, request), Catch::Contains("differ in epidermis.thickness_cm, which changes paths"));
    stacks[1].layers[1].thickness_cm = stacks[0].layers[1].thickness_cm;
    BiospecOptions random;
    random.estimator = AbsorptionEstimator::random_test;
    CHECK_THROWS_WITH(solve_biospec_sets(sets, request, random), Catch::Contains("absorption replay needs the weighted estimator"));
}

// ---- The model authors' behaviours and the Rayleigh turn rules, each in isolation (docs/BIOSPEC.md) ----

namespace {

// One layer between air and air (or matched media), reflector off, no absorbers unless set.
LayerStack single_layer(CrossingScattering crossing, double n, double thickness_cm) {
    LayerStack s;
    s.name = "slab";
    TissueLayer l;
    l.name = "slab";
    l.thickness_cm = thickness_cm;
    l.refractive_index = n;
    l.crossing = crossing;
    s.layers = {l};
    s.bottom = BottomBoundary::exit;
    s.model.baseline_absorption = false;
    return s;
}

// Hemispherical reflectance of Lambertian light meeting an interface n_from -> n_to: 2 int_0^1 F(mu) mu dmu
// (midpoint rule on the Fresnel formula).
double diffuse_fresnel(double n_from, double n_to) {
    constexpr int steps = 20000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double mu = (i + 0.5) / steps;
        sum += 2.0 * fresnel_reflectance(mu, n_from, n_to) * mu / steps;
    }
    return sum;
}

bool within(const Estimate& e, double expected, double sigmas = 4.0, double margin = 1e-12) {
    return std::abs(e.value - expected) < sigmas * e.stderr + margin;
}

}  // namespace

TEST_CASE("behaviour 1: upward interfaces with swapped indices lose total internal reflection", "[biospec_solver][authors]") {
    // A non-absorbing cosine-scattering slab (n 1.55, air both sides): every crossing re-draws a Lambertian direction,
    // so a ray leaves downward with t_d = 1 - r_int and upward with t_u per crossing, r_int / r_ext the diffuse
    // Fresnel reflectances from inside / outside. R = F0 + (1 - F0) (1 - t_d) t_u / (1 - (1 - t_d)(1 - t_u)).
    const double n = 1.55;
    const double f0 = std::pow((n - 1.0) / (n + 1.0), 2);
    const double r_int = diffuse_fresnel(n, 1.0), r_ext = diffuse_fresnel(1.0, n);
    REQUIRE(r_int > 0.5);  // TIR beyond 40 deg
    const auto expected = [&](double t_d, double t_u) { return f0 + (1.0 - f0) * (1.0 - t_d) * t_u / (1.0 - (1.0 - t_d) * (1.0 - t_u)); };
    SpectralRequest request = all_quantities({550.0}, 400'000);
    for (const bool swapped : {false, true}) {
        INFO("swapped = " << swapped);
        auto stack = single_layer(CrossingScattering::cosine, n, 0.01);
        stack.model.swapped_upward_indices = swapped;
        const auto w = solve_biospec(stack, request).wavelengths.front();
        CHECK(within(w.reflectance, expected(1.0 - r_int, swapped ? 1.0 - r_ext : 1.0 - r_int)));
        CHECK(energy(w) == Approx(1.0).margin(1e-12));
    }
}

TEST_CASE("behaviour 3: with the bottom Fresnel test off, light leaves the bottom at once", "[biospec_solver][authors]") {
    auto stack = single_layer(CrossingScattering::cosine, 1.55, 0.01);
    stack.model.bottom_exit_fresnel = false;
    const auto w = solve_biospec(stack, all_quantities({550.0}, 100'000)).wavelengths.front();
    // Only the first-surface reflection comes back; everything that entered is transmitted.
    CHECK(w.reflectance.value == w.specular_reflectance.value);
    CHECK(w.transmittance.value == Approx(1.0 - w.reflectance.value).margin(1e-12));
    CHECK(within(w.reflectance, std::pow(0.55 / 2.55, 2)));
}

TEST_CASE("behaviour 4: a reversing SC perturbation leaves as reflectance, unabsorbed", "[biospec_solver][authors]") {
    // A thick, strongly absorbing, index-matched SC at 80 deg incidence: a ray survives only if its first perturbation
    // (polar theta from the measured profile, uniform azimuth) turns it upward, which happens with probability
    // P = int p(theta) acos(min(1, cot a cot theta)) / pi dtheta, a = 80 deg. With re-drawing (the specification)
    // nothing comes back.
    auto stack = single_layer(CrossingScattering::measured_stratum_corneum, 1.0, 0.5);
    stack.layers[0].melanosome_fraction = 0.3;
    REQUIRE(absorption_per_cm(stack.layers[0], 546.0, stack.model) * 0.5 > 50.0);
    const double a = 80.0 * std::numbers::pi / 180.0;
    const auto& profile = MeasuredProfile::stratum_corneum();
    double expected = 0.0;
    constexpr int steps = 20000;
    for (int i = 0; i < steps; ++i) {
        const double theta_deg = 62.5 * (i + 0.5) / steps;
        const double x = 1.0 / std::tan(a) / std::tan(theta_deg * std::numbers::pi / 180.0);
        expected += profile.pdf_theta(546.0, theta_deg) * 62.5 / steps * (x >= 1.0 ? 0.0 : std::acos(x) / std::numbers::pi);
    }
    REQUIRE(expected > 0.05);
    auto request = all_quantities({546.0}, 200'000);
    request.incidence_deg = 80.0;
    stack.model.redraw_reversals_in_stratum_corneum = false;
    const auto kept = solve_biospec(stack, request).wavelengths.front();
    CHECK(within(kept.reflectance, expected, 4.0, 0.005));  // 0.005: the 1000-entry table against the continuous profile
    CHECK(energy(kept) == Approx(1.0).margin(1e-12));
    stack.model.redraw_reversals_in_stratum_corneum = true;
    CHECK(solve_biospec(stack, request).wavelengths.front().reflectance.value < 1e-6);
}

TEST_CASE("Rayleigh turn rules: sampled depth, whole crossing, no absorption against their integrals", "[biospec_solver][rayleigh]") {
    // An index-matched dermal slab (n 1, Rayleigh by collagen + cosine), normal incidence, reflector off: light comes
    // back only from rays turned upward on their first crossing. With beta the turn coefficient (Rayleigh, plus the
    // Mie reduced scattering when set), mu the absorption, d the thickness and p(c) = 3/8 (1 + c^2) the phase function
    // (c = cos of the new direction):
    //   sampled depth:  R = int_0^d beta e^-(beta + mu) z int_{-1}^0 p(c) e^(-mu z / |c|) dc dz
    //   whole crossing: R = (1 - e^-beta d) int_{-1}^0 p(c) e^(-mu d / |c|) dc
    //   no absorption:  R = (1 - e^-beta d) / 2
    // Rayleigh alone at 500 nm; at 1600 nm Rayleigh is 1/105 of that and the Mie part, a (lambda / 500)^-b, turns.
    for (const auto& [nm, mie_at_500nm] : std::vector<std::pair<double, double>>{{500.0, 0.0}, {1600.0, 60.0}}) {
        auto stack = single_layer(CrossingScattering::rayleigh_cosine, 1.0, 0.02);
        stack.layers[0].blood_fraction = 0.1;
        stack.layers[0].water_fraction = 0.9;  // the absorber at 1600 nm
        stack.layers[0].mie_reduced_scattering_per_cm_at_500nm = mie_at_500nm;
        const double beta = rayleigh_coefficient_per_cm(stack.layers[0], nm) +
                            mie_at_500nm * std::pow(nm / 500.0, -stack.layers[0].mie_reduced_scattering_power);
        const double mu = absorption_per_cm(stack.layers[0], nm, stack.model);
        const double d = 0.02;
        REQUIRE(beta * d > 0.3);
        REQUIRE(mu * d > 0.1);
        constexpr int nz = 2000, nc = 2000;
        const auto up = [&](double depth) {
            double s = 0.0;
            for (int j = 0; j < nc; ++j) {
                const double c = (j + 0.5) / nc;  // |cos|
                s += 0.375 * (1.0 + c * c) * std::exp(-mu * depth / c) / nc;
            }
            return s;
        };
        double sampled = 0.0;
        for (int i = 0; i < nz; ++i) {
            const double z = d * (i + 0.5) / nz;
            sampled += beta * std::exp(-(beta + mu) * z) * up(z) * d / nz;
        }
        const double hit = 1.0 - std::exp(-beta * d);
        const std::vector<std::pair<RayleighTurn, double>> rules{
            {RayleighTurn::sampled_depth, sampled}, {RayleighTurn::whole_crossing, hit * up(d)}, {RayleighTurn::no_absorption, hit * 0.5}};
        for (const auto& [rule, expected] : rules) {
            INFO(nm << " nm, Mie " << mie_at_500nm << " /cm at 500 nm, " << to_string(rule) << ": expected " << expected);
            stack.model.rayleigh_turn = rule;
            const auto w = solve_biospec(stack, all_quantities({nm}, 400'000)).wavelengths.front();
            INFO("got " << w.reflectance.value << " +- " << w.reflectance.stderr << " T " << w.transmittance.value);
            CHECK(within(w.reflectance, expected, 4.0, 1e-4));
            CHECK(energy(w) == Approx(1.0).margin(1e-12));
        }
    }
}

TEST_CASE("measurement geometries: SCE is SCI without the first surface, 0/45 of a perfect diffuser is 1", "[biospec_solver][geometry]") {
    auto request = all_quantities({450.0, 650.0}, 50'000);
    const auto skin = preset("biospec-moderately");
    const auto sci = solve_biospec(skin, request);
    request.geometry = MeasurementGeometry::sce;
    const auto sce = solve_biospec(skin, request);
    for (std::size_t w = 0; w < 2; ++w) {
        CHECK(sce.wavelengths[w].reflectance.value + sce.wavelengths[w].specular_reflectance.value ==
              Approx(sci.wavelengths[w].reflectance.value).margin(1e-12));
    }
    // A non-absorbing cosine slab with n = 1 on a Lambertian reflector is a perfect diffuser: R(0/45) = 1.
    auto diffuser = single_layer(CrossingScattering::cosine, 1.0, 0.01);
    diffuser.bottom = BottomBoundary::diffuse_reflector;
    request.geometry = MeasurementGeometry::zero_45;
    request.quantities = Quantities{};
    const auto w = solve_biospec(diffuser, request).wavelengths.front();
    CHECK(within(w.reflectance, 1.0));
    CHECK(w.reflectance.stderr > 0.0);
    request.incidence_deg = 8.0;
    CHECK_THROWS_WITH(solve_biospec(diffuser, request), "geometry 0-45 defines normal incidence; incidence 8 deg given");
}

TEST_CASE("path recording: the white limit conserves energy and re-weighting matches the walk", "[biospec_solver][paths]") {
    auto skin = preset("biospec-lightly");
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list({420.0, 600.0});
    request.max_rays_per_wavelength = 40'000;
    const auto paths = record_biospec_paths(skin, request);
    REQUIRE(paths);
    const auto walked = solve_biospec(skin, request);
    for (std::size_t w = 0; w < 2; ++w) {
        const auto& p = (*paths)[w];
        CHECK(p.rays == 40'000);
        const std::vector<double> ones(p.layers(), 1.0);
        // No absorption and a reflector: every ray leaves the top.
        CHECK(p.reflectance(std::vector<double>(p.layers(), 0.0), ones).value == Approx(1.0).margin(1e-12));
        std::vector<double> mu;
        for (const auto& l : skin.layers) mu.push_back(absorption_per_cm(l, request.wavelengths[w], skin.model));
        const auto replayed = p.reflectance(mu, ones);
        const auto& direct = walked.wavelengths[w].reflectance;
        CHECK(std::abs(replayed.value - direct.value) < 4.0 * std::hypot(replayed.stderr, direct.stderr));
    }
}
