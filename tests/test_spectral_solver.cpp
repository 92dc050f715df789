// The solver interface: the registry, what each solver declares, the central refusals and the provenance.
#include <catch2/catch.hpp>

#include "solvers/spectral_solver.hpp"
#include "thread_work_share.hpp"
#include "materials/material_file.hpp"
#include "materials/path_key.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

#include <fmt/format.h>
#include <array>
#include <cmath>
#include <optional>

using namespace skinspec;

namespace {

SolverRequest one_wavelength(std::uint64_t rays = 2000) {
    SolverRequest r;
    r.spectral.wavelengths = WavelengthGrid::list({550.0});
    r.fixed_rays_per_wavelength = rays;
    return r;
}

}  // namespace

TEST_CASE("the registry lists every solver once, by name", "[solver]") {
    CHECK(solver_names() == "biospec, rte, adding-doubling, biospec-adding-doubling, matched-multipole, multipole, dipole");
    for (const auto* s : solver_registry()) CHECK(&find_solver(s->name()) == s);
    CHECK_THROWS_WITH(find_solver("tripole"), Catch::Contains("--mode: 'tripole' is not a solver (allowed: biospec, rte, adding-doubling, biospec-adding-doubling, matched-multipole, multipole, dipole)"));
}

TEST_CASE("a request for what a solver does not declare is refused with one message", "[solver]") {
    const auto skin = load_material("biospec-lightly");
    const auto bands = load_material("jensen2001-skin1");
    auto brdf = one_wavelength();
    brdf.spectral.quantities.angular = true;
    CHECK_THROWS_WITH(solve_spectrum(find_solver("rte"), skin, brdf),
                      "solver 'rte' does not compute brdf (it computes R, T, A; brdf is computed by: biospec)");
    auto absorptance = SolverRequest{};
    absorptance.spectral.quantities.absorptance = true;
    CHECK_THROWS_WITH(solve_spectrum(find_solver("multipole"), skin, absorptance), Catch::Contains("solver 'multipole' does not compute A"));
    auto estimator = SolverRequest{};
    estimator.switches.estimator = AbsorptionEstimator::random_test;
    CHECK_THROWS_WITH(solve_spectrum(find_solver("dipole"), skin, estimator),
                      "solver 'dipole' does not take the switch 'estimator' (taken by: biospec)");
    auto fold = SolverRequest{};
    fold.switches.fold_into_skin = FoldIntoSkin::resample;
    CHECK_THROWS_WITH(solve_spectrum(find_solver("multipole"), skin, fold), Catch::Contains("does not take the switch 'fold-into-skin'"));
    auto rough = one_wavelength();
    rough.switches.surface_roughness = 0.3;
    CHECK_THROWS_WITH(solve_spectrum(find_solver("biospec"), skin, rough), Catch::Contains("taken by: multipole, dipole"));
    CHECK_THROWS_WITH(solve_spectrum(find_solver("adding-doubling"), bands, SolverRequest{}),
                      Catch::Contains("solver 'adding-doubling' needs a layered material; 'jensen2001-skin1' is a homogeneous material given per band"));
    CHECK_THROWS_WITH(solve_spectrum(find_solver("dipole"), skin, one_wavelength()),
                      Catch::Contains("solver 'dipole' is deterministic: it takes no standard-error target or ray count"));
    auto target = SolverRequest{};
    target.spectral.stderr_target = 0.01;
    CHECK_THROWS_WITH(solve_spectrum(find_solver("multipole"), skin, target), Catch::Contains("is deterministic"));
    CHECK_THROWS_WITH(solve_profiles(find_solver("biospec"), skin, ProfileRequest{WavelengthGrid::list({550.0}), {0.0, 1.0}, false, {}}),
                      "solver 'biospec' does not compute radial profiles R(r) (solvers that do: rte, matched-multipole, multipole, dipole)");
}

TEST_CASE("a Monte Carlo result needs 100 rays per wavelength for its standard error (one ray reported R +- 0)", "[solver]") {
    const auto skin = load_material("biospec-lightly");
    for (const char* name : {"biospec", "rte"}) {
        CHECK_THROWS_WITH(solve_spectrum(find_solver(name), skin, one_wavelength(1)),
                          "--rays = 1 is outside [100, 1125899906842624]: a Monte Carlo standard error needs at least 100 rays per wavelength");
        auto budget = SolverRequest{};
        budget.spectral.stderr_target = 0.01;
        budget.spectral.max_rays_per_wavelength = 99;
        CHECK_THROWS_WITH(solve_spectrum(find_solver(name), skin, budget), Catch::Contains("--max-rays = 99 is outside [100, "));
    }
    // The fewest give a standard error from the rays' spread.
    CHECK(solve_spectrum(find_solver("biospec"), skin, one_wavelength(minimum_rays_per_wavelength)).wavelengths.front().reflectance.stderr > 0.0);
    CHECK_THROWS_WITH(solve_profiles(find_solver("rte"), skin, ProfileRequest{WavelengthGrid::list({550.0}), {0.0, 1.0}, false, {}, 99}),
                      Catch::Contains("--rays = 99 is outside [100, "));
}

TEST_CASE("every declared capability is served", "[solver]") {
    const auto skin = load_material("biospec-lightly");  // every skin preset describes itself for every solver
    for (const auto* solver : solver_registry()) {
        const auto& caps = solver->capabilities();
        SolverRequest request;
        request.spectral.wavelengths = WavelengthGrid::list({550.0});
        request.spectral.quantities = caps.quantities;
        if (caps.uncertainty) request.fixed_rays_per_wavelength = 500;
        const auto result = solve_spectrum(*solver, skin, request);
        REQUIRE(result.wavelengths.size() == 1);
        CHECK(result.has_uncertainty == caps.uncertainty);
        const auto& w = result.wavelengths.front();
        if (caps.quantities.absorptance) CHECK(w.absorptance_layers.size() == result.layer_names.size());
        if (caps.quantities.angular) CHECK_FALSE(w.brdf_per_sr.empty());
        if (caps.uncertainty) CHECK(w.rays == 500);
        // Energy: R + T + sum A (+ A_surface) = 1 where every term is computed (a conservation law).
        if (caps.quantities.absorptance) {
            double sum = w.reflectance.value + w.transmittance.value + w.absorptance_surface.value;
            for (const auto& a : w.absorptance_layers) sum += a.value;
            CHECK(sum == Approx(1.0).margin(1e-9));
        }
        // Every geometry it declares is served; every switch it declares is taken and every other one refused.
        for (const auto g : caps.geometries) {
            auto in_geometry = request;
            in_geometry.spectral.geometry = g;
            in_geometry.spectral.quantities = Quantities{true, false, false, false};
            CHECK(std::isfinite(solve_spectrum(*solver, skin, in_geometry).wavelengths.front().reflectance.value));
        }
        for (const auto& d : switch_descriptors()) {
            if (!d.parse) continue;
            auto with_switch = request;
            d.parse(with_switch.switches, d.example, std::string(d.name));
            INFO(solver->name() << " --" << d.name << " " << d.example);
            if (std::find(caps.switches.begin(), caps.switches.end(), d.id) != caps.switches.end()) {
                CHECK(std::isfinite(solve_spectrum(*solver, skin, with_switch).wavelengths.front().reflectance.value));
            } else {
                CHECK_THROWS_WITH(solve_spectrum(*solver, skin, with_switch), Catch::Contains("does not take the switch '" + std::string(d.name) + "'"));
            }
        }
        // Radial profiles where declared, refused elsewhere.
        const ProfileRequest profile{WavelengthGrid::list({550.0}), {0.0, 0.5, 1.0}, false, {}, caps.uncertainty ? std::optional<std::uint64_t>(2000) : std::nullopt, 1};
        if (caps.radial_profiles) CHECK(solve_profiles(*solver, skin, profile).channels.size() == 1);
        else CHECK_THROWS_WITH(solve_profiles(*solver, skin, profile), Catch::Contains("does not compute radial profiles"));
    }
}

TEST_CASE("every solver covers 250-2500 nm with finite reflectance in [0, 1] (issue 35)", "[solver]") {
    const auto skin = load_material("biospec-lightly");
    for (const auto* solver : solver_registry()) {
        INFO(solver->name());
        SolverRequest request;
        request.spectral.wavelengths = WavelengthGrid::list({250.0, 1000.0, 1450.0, 1940.0, 2500.0});
        if (solver->capabilities().uncertainty) request.fixed_rays_per_wavelength = 2000;
        const auto result = solve_spectrum(*solver, skin, request);
        REQUIRE(result.wavelengths.size() == 5);
        for (const auto& w : result.wavelengths) {
            INFO(w.wavelength_nm << " nm");
            CHECK(std::isfinite(w.reflectance.value));
            CHECK(w.reflectance.value >= 0.0);
            CHECK(w.reflectance.value <= 1.0);
        }
        // Water's 1450 and 1940 nm bands leave little more than the first-surface reflection.
        CHECK(result.wavelengths[2].reflectance.value < result.wavelengths[1].reflectance.value);
        CHECK(result.wavelengths[3].reflectance.value < 0.1);
    }
}

TEST_CASE("a result records its provenance: resolved material, overrides, solver, version, integers stay integers", "[solver]") {
    const std::vector<MaterialOverride> overrides{{"epidermis.melanosome_fraction", "0.03"}};
    const auto skin = load_material("biospec-moderately", overrides);
    auto request = one_wavelength(300);
    request.overrides = overrides;
    request.spectral.seed = 42;
    const auto result = solve_spectrum(find_solver("biospec"), skin, request);
    CHECK(result.provenance.solver == "biospec");
    REQUIRE(result.provenance.overrides.size() == 1);
    CHECK(result.provenance.overrides.front() == std::pair<std::string, std::string>{"epidermis.melanosome_fraction", "0.03"});
    CHECK(parse_material(*result.provenance.material_toml, "provenance") == skin);
    CHECK(std::get<std::uint64_t>(result.settings.at("seed")) == 42);
    CHECK(std::get<std::uint64_t>(result.settings.at("max_rays_per_wavelength")) == 300);
}

TEST_CASE("a sweep replays what only absorbs and traces anew what changes paths, results in order", "[solver]") {
    const auto& walk = find_solver("biospec");
    std::vector<SweepMember> members;
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{{"epidermis.melanosome_fraction", "0.02"},
                                                                                     {"epidermis.thickness_cm", "0.02"},
                                                                                     {"epidermis.melanosome_fraction", "0.1"}}) {
        const auto field = std::make_shared<const std::vector<std::string>>(std::vector<std::string>{key});
        members.push_back({std::make_shared<const Material>(load_material("biospec-moderately")), {field, {std::stod(value)}}, nullptr, {}});
    }
    // With T (and A) asked, the replay: each member equals its own run.
    auto request = one_wavelength(2000);
    request.spectral.quantities = {true, true, true, false};
    const auto results = solve_sweep(walk, members, request);
    REQUIRE(results.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
        // Each equals its own run (replayed or not), and records its varied field.
        const auto alone = solve_spectrum(walk, members[i].material(), request);
        CHECK(results[i].wavelengths.front().reflectance.value == Approx(alone.wavelengths.front().reflectance.value).margin(1e-12));
        CHECK(results[i].provenance.varied == members[i].varied);
        CHECK(all_overrides(results[i].provenance).back().second == std::vector<std::string>{"0.02", "0.02", "0.1"}[i]);
    }
    CHECK(std::get<std::uint64_t>(results[0].settings.at("absorption_sets_traced_together")) == 2);
    CHECK(std::get<std::string>(results[0].settings.at("absorption_sets_estimator")).starts_with("replay"));
    CHECK(std::get<std::uint64_t>(results[1].settings.at("absorption_sets_traced_together")) == 1);
    // R alone: the replayed members re-weight recorded paths (another estimator of the same R): each agrees with its
    // own run within 4 combined standard errors, and says how it was estimated.
    auto r_only = one_wavelength(20000);
    const auto reweighed = solve_sweep(walk, members, r_only);
    for (const std::size_t i : {std::size_t{0}, std::size_t{2}}) {
        const auto alone = solve_spectrum(walk, members[i].material(), r_only).wavelengths.front().reflectance;
        const auto swept = reweighed[i].wavelengths.front().reflectance;
        CHECK(std::abs(swept.value - alone.value) <= 4.0 * std::hypot(swept.stderr, alone.stderr));
        CHECK(std::get<std::string>(reweighed[i].settings.at("absorption_sets_estimator")).starts_with("recorded paths"));
    }
    const auto& replay = walk.capabilities().replay_fields;
    CHECK(std::find(replay.begin(), replay.end(), "LAYER.melanosome_fraction") != replay.end());
    CHECK(std::find(replay.begin(), replay.end(), "LAYER.thickness_cm") == replay.end());
}

TEST_CASE("sweep members: every combination, the first axis fastest, each checked before any ray", "[solver]") {
    const auto& walk = find_solver("biospec");
    const auto request = one_wavelength(100);
    const std::vector<SweepAxis> axes{{"epidermis.melanosome_fraction", {0.01, 0.02, 0.04}}, {"dermis.blood_fraction", {0.002, 0.01}}};
    const auto base = load_material("biospec-moderately");
    const auto members = sweep_members(walk, request, axes, {}, base);
    REQUIRE(members.size() == 6);
    CHECK(*members[1].varied.fields == std::vector<std::string>{"epidermis.melanosome_fraction", "dermis.blood_fraction"});
    CHECK(members[1].varied.values == std::vector<double>{0.02, 0.002});
    CHECK(members[3].varied.values.back() == 0.01);
    // The members share one list of the swept fields' names.
    CHECK(members[1].varied.fields == members[4].varied.fields);
    CHECK(members[1].position == std::vector<std::size_t>{1, 0});
    CHECK(members[5].position == std::vector<std::size_t>{2, 1});
    CHECK(std::get<double>(material_field(members[5].material(), "epidermis.melanosome_fraction")) == 0.04);
    CHECK(members[5].overrides().front().value == "0.04");
    // One base text for the whole sweep; each result records it with its member's overrides.
    CHECK(members[0].base_toml == members[5].base_toml);
    CHECK(*members[0].base_toml == to_toml(base));
    CHECK(with_overrides(parse_material(*members[5].base_toml, "base"), members[5].overrides()) == members[5].material());
    CHECK(sweep_members(walk, request, {}, {}, base).size() == 1);
    const auto cut = sweep_members(walk, request, {}, {"stratum_corneum", "epidermis"}, base);
    CHECK(std::get<LayerStack>(cut[0].material()).layers.size() == 2);
    CHECK_THROWS_WITH(sweep_members(walk, request, {{"epidermis.melanosome_fraction", {0.01, 2.0}}}, {}, base), Catch::Contains("= 2 is outside [0, 1]"));
    auto t_request = request;
    t_request.spectral.quantities.angular = true;
    CHECK_THROWS_WITH(sweep_members(find_solver("dipole"), t_request, axes, {}, base), Catch::Contains("does not compute brdf"));
    CHECK_THROWS_WITH(sweep_members(find_solver("dipole"), SolverRequest{}, {}, {"epidermis"}, load_material("jensen2001-skin1")),
                      Catch::Contains("homogeneous and has no layers"));
}

TEST_CASE("solve groups: replaying solvers group what shares paths, the others solve each material alone", "[solver]") {
    // Two melanin levels and another epidermis, on the preset's derived volumetric description or on its own one.
    const auto three = [](const char* derived) {
        std::vector<Material> m;
        for (const char* v : {"0.02", "0.05"}) {
            m.push_back(load_material("biospec-moderately", {{"epidermis.melanosome_fraction", v}, {"model.volumetric_matched_to_biospec", derived}}));
        }
        m.push_back(load_material("biospec-moderately", {{"epidermis.thickness_cm", "0.02"}, {"model.volumetric_matched_to_biospec", derived}}));
        return m;
    };
    const auto materials = three("true"), own = three("false");
    std::vector<const Material*> pointers, own_pointers;
    for (const auto& m : materials) pointers.push_back(&m);
    for (const auto& m : own) own_pointers.push_back(&m);
    const auto request = one_wavelength(100);
    using Groups = std::vector<std::vector<std::size_t>>;
    CHECK(find_solver("biospec").solve_groups(pointers, request) == Groups{{0, 1}, {2}});
    // The derived description's dermal scattering follows the absorbers (path_key.hpp): the volumetric walk shares
    // paths between melanin levels only on the layers' own description.
    CHECK(find_solver("rte").solve_groups(pointers, request) == Groups{{0}, {1}, {2}});
    CHECK(find_solver("rte").solve_groups(own_pointers, request) == Groups{{0, 1}, {2}});
    CHECK(find_solver("multipole").solve_groups(pointers, {}) == Groups{{0}, {1}, {2}});
    auto per_crossing = request;
    per_crossing.switches.estimator = AbsorptionEstimator::random_test;
    CHECK(find_solver("biospec").solve_groups(pointers, per_crossing) == Groups{{0}, {1}, {2}});
}

TEST_CASE("a sweep shared among processes gives rank 0 the one-process results bit for bit", "[solver]") {
    const auto base = load_material("biospec-moderately");
    const std::vector<SweepAxis> axes{{"epidermis.melanosome_fraction", {0.01, 0.05}}, {"epidermis.thickness_cm", {0.008, 0.01, 0.012}}};
    for (const char* solver : {"biospec", "rte", "multipole"}) {
        const auto& s = find_solver(solver);
        const auto request = s.capabilities().uncertainty ? one_wavelength(500) : SolverRequest{};
        const auto members = sweep_members(s, request, axes, {}, base);
        const auto one = solve_sweep(s, members, request);
        const auto shared = testing::run_shared<std::vector<SpectralResult>>(2, [&](const WorkShare& share) { return solve_sweep(s, members, request, &share); });
        REQUIRE(shared.size() == one.size());
        for (std::size_t i = 0; i < one.size(); ++i) {
            CHECK(shared[i].wavelengths.front().reflectance.value == one[i].wavelengths.front().reflectance.value);
            CHECK(shared[i].wavelengths.front().reflectance.stderr == one[i].wavelengths.front().reflectance.stderr);
            CHECK(shared[i].settings == one[i].settings);
            CHECK(shared[i].provenance.varied == one[i].provenance.varied);
            CHECK(*shared[i].provenance.material_toml == *one[i].provenance.material_toml);
        }
    }
}

namespace {

// A value of `key` other than `value` that the material accepts (InputError-free), as the material and the value's
// text, or nullopt.
std::optional<std::pair<Material, std::string>> perturbed(const Material& base, const std::string& key, const FieldValue& value) {
    std::vector<std::string> candidates;
    if (const auto* b = std::get_if<bool>(&value)) candidates = {*b ? "false" : "true"};
    else if (const auto* d = std::get_if<double>(&value)) {
        for (const double v : {*d * 1.3, *d * 0.7, *d + 0.1, *d - 0.1, 10.0}) candidates.push_back(fmt::format("{}", v));
    }
    for (const auto& c : candidates) {
        try {
            auto m = with_overrides(base, {{key, c, "--vary"}});
            if (!(m == base)) return std::pair{std::move(m), c};
        } catch (const InputError&) {
        }
    }
    return std::nullopt;
}

}  // namespace

TEST_CASE("a two-member sweep equals two direct runs for every field of every layer in every solver", "[solver][sweep]") {
    // Every description present: papillary dermis with a reduced-scattering power law (volumetric mu_s derived from
    // it), reticular dermis with its own volumetric power law, so that a field missing from replay grouping shows.
    auto stack = std::get<LayerStack>(load_material("biospec-lightly"));
    stack.layers[2].reduced = ReducedScattering{"", 40.0, 1.0};
    stack.layers[3].volumetric = VolumetricScattering{150.0, 1.0, PhaseFunctionKind::henyey_greenstein, 0.8, VolumetricSource::power_law};
    const Material base = stack;
    std::size_t fields = 0;
    for (const auto& key : material_keys(base)) {
        const auto value = material_field(base, key);
        const auto changed = perturbed(base, key, value);
        if (!changed) continue;
        const auto* other = &changed->first;
        ++fields;
        const std::vector<const Material*> pair{&base, other};
        for (const auto* solver : solver_registry()) {
            if (!solver->capabilities().layered_materials) continue;
            const auto request = solver->capabilities().uncertainty ? one_wavelength(4000) : SolverRequest{};
            auto single = request;
            single.spectral.wavelengths = WavelengthGrid::list({550.0});
            const std::vector<SweepMember> members{{std::make_shared<const Material>(base), {}, nullptr, {}}, {std::make_shared<const Material>(*other), {}, nullptr, {}}};
            INFO(solver->name() << " " << key << ": " << material_field(*other, key).index());
            std::vector<SpectralResult> swept;
            try {
                swept = solve_sweep(*solver, members, single);
            } catch (const InputError&) {
                // A setting the solver does not model (e.g. an authors'-code behaviour): refused alike when run directly.
                CHECK_THROWS_AS(solve_spectrum(*solver, *other, single), InputError);
                continue;
            }
            REQUIRE(swept.size() == 2);
            // Grouping follows the declaration: absorption-only fields share one trace, every other field is traced anew
            // (and every field for the volumetric walk on a derived description: its dermal mu_s follows the absorbers).
            if (!solver->capabilities().replay_fields.empty()) {
                const bool derived_walk = solver->name() == "rte" && stack.model.volumetric_matched_to_biospec;
                CHECK(solver->solve_groups(pair, single).size() == (is_absorption_only_key(key) && !derived_walk ? 1u : 2u));
            }
            for (std::size_t i = 0; i < 2; ++i) {
                const auto direct = solve_spectrum(*solver, *pair[i], single);
                const auto& a = swept[i].wavelengths.front().reflectance;
                const auto& b = direct.wavelengths.front().reflectance;
                if (solver->capabilities().uncertainty) CHECK(std::abs(a.value - b.value) <= 4.5 * std::hypot(a.stderr, b.stderr) + 1e-12);
                else CHECK(a.value == Approx(b.value).epsilon(1e-12).margin(1e-15));
            }
        }
    }
    CHECK(fields > 60);
}

TEST_CASE("an override of a field the solver does not read is refused, and no such field changes its result", "[solver]") {
    // Every description present, as in the sweep test: papillary dermis with a reduced-scattering power law (its
    // volumetric mu_s derived from it), reticular dermis with its own volumetric power law.
    auto stack = std::get<LayerStack>(load_material("biospec-lightly"));
    stack.layers[2].reduced = ReducedScattering{"", 40.0, 1.0};
    stack.layers[3].volumetric = VolumetricScattering{150.0, 1.0, PhaseFunctionKind::henyey_greenstein, 0.8, VolumetricSource::power_law};
    const Material base = stack;
    std::vector<std::pair<std::string, std::pair<Material, std::string>>> cases;
    for (const auto& key : material_keys(base)) {
        if (auto changed = perturbed(base, key, material_field(base, key))) cases.emplace_back(key, std::move(*changed));
    }
    // The named fields of the three descriptions.
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{{"epidermis.scattering", "cosine"},
                                                                                     {"epidermis.volumetric_phase", "isotropic"},
                                                                                     {"reticular_dermis.reduced_scattering_table", "salomatina_hypodermis"}}) {
        cases.emplace_back(key, std::pair{with_overrides(base, {{key, value}}), value});
    }
    std::size_t refused = 0;
    for (const auto* solver : solver_registry()) {
        if (!solver->capabilities().layered_materials) continue;
        auto request = solver->capabilities().uncertainty ? one_wavelength(2000) : SolverRequest{};
        request.spectral.wavelengths = WavelengthGrid::list({420.0, 550.0, 680.0});
        request.spectral.incidence_deg = 40.0;  // the skin fold acts on an oblique beam
        std::optional<SpectralResult> unchanged;
        for (const auto& [key, changed] : cases) {
            const auto& [other, text] = changed;
            if (reads_field(solver->capabilities(), other, key)) continue;
            INFO(solver->name() << " " << key << " = " << text);
            // Refused when asked for ...
            auto asked = request;
            asked.overrides = {{key, text}};
            CHECK_THROWS_WITH(solve_spectrum(*solver, other, asked), Catch::Contains("which solver '" + std::string(solver->name()) + "' does not read"));
            ++refused;
            // ... and truly not read: the result is the base's to the bit (the walks draw the same random numbers).
            try {
                if (!unchanged) unchanged = solve_spectrum(*solver, base, request);
                const auto result = solve_spectrum(*solver, other, request);
                for (std::size_t w = 0; w < result.wavelengths.size(); ++w) {
                    CHECK(result.wavelengths[w].reflectance.value == unchanged->wavelengths[w].reflectance.value);
                }
            } catch (const InputError&) {
                // An authors'-code behaviour the solver does not model: refused as it always was.
            }
        }
    }
    CHECK(refused > 40);
}

TEST_CASE("a layer field read only with one kind of scattering is refused where the layer scatters otherwise, and changes nothing there", "[solver]") {
    const auto base = load_material("biospec-lightly");
    auto no_rayleigh = base;
    std::get<LayerStack>(no_rayleigh).model.dermal_rayleigh = false;
    std::size_t refused = 0;
    for (const auto* solver : solver_registry()) {
        if (!solver->capabilities().layered_materials || !reads_field(solver->capabilities(), base, "epidermis.hg_g")) continue;
        auto request = solver->capabilities().uncertainty ? one_wavelength(2000) : SolverRequest{};
        for (const Material* material : std::array<const Material*, 2>{&base, &no_rayleigh}) {
            const auto& stack = std::get<LayerStack>(*material);
            std::optional<SpectralResult> unchanged;
            for (const auto& f : layer_number_fields()) {
                if (!f.read_with) continue;
                for (const auto& layer : stack.layers) {
                    if (crossing_in_effect(layer, stack.model) == *f.read_with) continue;
                    const auto key = layer.name + "." + std::string(f.key);
                    const auto value = format_number(f.range.contains(0.5) ? 0.5 : 2.0);
                    INFO(solver->name() << " " << key << " dermal_rayleigh " << stack.model.dermal_rayleigh);
                    auto changed = *material;
                    std::get<LayerStack>(changed).layers[&layer - stack.layers.data()].*(f.member) = std::stod(value);
                    auto asked = request;
                    asked.overrides = {{key, value}};
                    CHECK_THROWS_WITH(solve_spectrum(*solver, changed, asked), Catch::Contains("is read only with scattering = " + std::string(to_string(*f.read_with))));
                    ++refused;
                    if (!unchanged) unchanged = solve_spectrum(*solver, *material, request);
                    CHECK(solve_spectrum(*solver, changed, request).wavelengths.front().reflectance.value == unchanged->wavelengths.front().reflectance.value);
                }
            }
        }
    }
    CHECK(refused > 20);
}

TEST_CASE("radial profiles refuse an override the solver does not read, as spectra do", "[solver]") {
    const auto base = load_material("biospec-lightly");
    const auto other = with_overrides(base, {{"epidermis.hg_g", "0.5"}});
    ProfileRequest request;
    request.radii_mm = {0.1, 0.5};
    request.overrides = {{"epidermis.hg_g", "0.5"}};
    CHECK_THROWS_WITH(solve_profiles(find_solver("multipole"), other, request), Catch::Contains("which solver 'multipole' does not read"));
    // Not read indeed: the profile is the base's to the bit.
    request.overrides.clear();
    CHECK(solve_profiles(find_solver("multipole"), other, request).channels.front().reflectance_per_mm2 ==
          solve_profiles(find_solver("multipole"), base, request).channels.front().reflectance_per_mm2);
    request.overrides = {{"epidermis.melanosome_fraction", "0.1"}};
    CHECK_NOTHROW(solve_profiles(find_solver("multipole"), with_overrides(base, {{"epidermis.melanosome_fraction", "0.1"}}), request));
}

TEST_CASE("a solver that reads only the top layer's refractive index refuses an override of a deeper one's", "[solver]") {
    const auto base = load_material("biospec-lightly");
    const auto& stack = std::get<LayerStack>(base);
    std::size_t refused = 0;
    for (const auto* solver : solver_registry()) {
        if (!solver->capabilities().layered_materials || solver->capabilities().layer_refractive_indices) continue;
        const auto unchanged = solve_spectrum(*solver, base, SolverRequest{});
        for (std::size_t k = 0; k < stack.layers.size(); ++k) {
            const auto key = stack.layers[k].name + ".refractive_index";
            INFO(solver->name() << " " << key);
            const auto other = with_overrides(base, {{key, "1.6"}});
            SolverRequest asked;
            asked.overrides = {{key, "1.6"}};
            if (k == 0) {
                // The top layer's index is read: the surface's Fresnel reflection changes.
                CHECK(solve_spectrum(*solver, other, asked).wavelengths.front().specular_reflectance.value !=
                      unchanged.wavelengths.front().specular_reflectance.value);
                continue;
            }
            CHECK_THROWS_WITH(solve_spectrum(*solver, other, asked), Catch::Contains("does not read a deeper layer's"));
            ++refused;
            // ... and truly not read.
            CHECK(solve_spectrum(*solver, other, SolverRequest{}).wavelengths.front().reflectance.value == unchanged.wavelengths.front().reflectance.value);
        }
    }
    CHECK(refused >= 3);
}

TEST_CASE("a reduced-scattering sweep traces each value anew (issue 30)", "[solver][sweep]") {
    auto stack = std::get<LayerStack>(load_material("biospec-lightly"));
    stack.layers[2].reduced = ReducedScattering{"", 40.0, 1.0};
    std::vector<Material> materials;
    for (const char* v : {"20", "200"}) materials.push_back(with_overrides(Material{stack}, {{"papillary_dermis.reduced_scattering_per_cm_at_500nm", v}}));
    const std::vector<const Material*> pointers{&materials[0], &materials[1]};
    CHECK(find_solver("rte").solve_groups(pointers, one_wavelength()) == std::vector<std::vector<std::size_t>>{{0}, {1}});
    CHECK(path_difference(std::get<LayerStack>(materials[0]), std::get<LayerStack>(materials[1]), TracedPaths::volumetric) ==
          "papillary_dermis.reduced_scattering_per_cm_at_500nm");
}

TEST_CASE("progress of a sweep's parts is progress of the whole: never back, rays to come estimated", "[solver]") {
    std::vector<Progress> seen;
    PartProgress progress([&](const Progress& p) { seen.push_back(p); }, 3);
    for (std::size_t part = 0; part < 3; ++part) {
        const auto request = progress.part(SpectralRequest{}, part);
        // Each part reports from 0, as a solver does: 2 of 4 wavelengths, then all 4.
        request.on_progress(Progress{500, 1000, 2, 4});
        request.on_progress(Progress{1000, 1000, 4, 4});
        progress.finish_part();
    }
    REQUIRE(seen.size() == 6);
    CHECK(seen[0].rays_expected == 3000);  // this part's 1000, and as much for each of the two to come
    CHECK(seen[2].rays_done == 1500);
    CHECK(seen[2].rays_expected == 3000);
    CHECK(seen[5].wavelengths_done == 12);
    CHECK(seen[5].wavelengths_total == 12);
    for (std::size_t i = 1; i < seen.size(); ++i) {
        CHECK(seen[i].wavelengths_done >= seen[i - 1].wavelengths_done);
        CHECK(seen[i].rays_done >= seen[i - 1].rays_done);
    }
    // No whole: the part's request reports nothing.
    PartProgress silent({}, 2);
    CHECK(!silent.part(SpectralRequest{}, 0).on_progress);
}

TEST_CASE("on a description derived from the BioSpec one, the volumetric solvers read the BioSpec fields and only the dermal layers' own", "[spectral_solver]") {
    const auto check = [](const char* solver, const char* field) {
        const std::vector<MaterialOverride> overrides{parse_override("model.volumetric_matched_to_biospec=true"), parse_override(field)};
        check_overrides(find_solver(solver), load_material("biospec-lightly", overrides), overrides);
    };
    for (const char* solver : {"adding-doubling", "rte"}) {
        INFO(solver);
        CHECK_NOTHROW(check(solver, "dermis.collagen_fibre_fraction=0.3"));  // the match's target moves with it
        CHECK_NOTHROW(check(solver, "dermis.volumetric_g=0.9"));
        CHECK_THROWS_WITH(check(solver, "stratum_corneum.volumetric_phase=isotropic"),
                          Catch::Contains("model.volumetric_matched_to_biospec = true derives the volumetric description"));
        // The dermal layers' mu_s: one factor scales them, so their ratio stays (papillary vs reticular).
        CHECK_NOTHROW(check(solver, "papillary_dermis.reduced_scattering_table=salomatina_epidermis"));
        CHECK_THROWS_WITH(check(solver, "epidermis.reduced_scattering_table=salomatina_dermis"), Catch::Contains("only the dermal layers'"));
    }
    CHECK_THROWS_WITH(check("biospec", "dermis.volumetric_g=0.9"), Catch::Contains("does not read"));
}
