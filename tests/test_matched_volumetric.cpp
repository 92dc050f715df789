#include <catch2/catch.hpp>

#include <cmath>

#include "materials/material_file.hpp"
#include "materials/path_key.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/adding_doubling_spectrum.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"
#include "transport/adding_doubling/matched_volumetric.hpp"
#include "transport/biospec/biospec_solver.hpp"

using namespace skinspec;

namespace {

LayerStack matched(const char* name, std::vector<MaterialOverride> overrides = {}) {
    overrides.push_back(parse_override("model.volumetric_matched_to_biospec=true"));
    return std::get<LayerStack>(load_material(name, overrides));
}

SpectralRequest request(std::vector<double> nm) {
    SpectralRequest r;
    r.wavelengths = WavelengthGrid::list(std::move(nm));
    return r;
}

}  // namespace

// The independent check: two Monte Carlo codes, one tracing the BioSpec model's crossings, the other the derived
// (mu_s, phase) medium, agree within their standard errors plus the match's 16-channel quadrature.
TEST_CASE("the volumetric walk on the derived description agrees with the BioSpec walk", "[matched_volumetric]") {
    for (const char* name : {"biospec-lightly", "biospec-heavily"}) {
        const auto stack = matched(name);
        auto r = request({420.0, 560.0, 690.0});
        r.stderr_target = 0.002;
        r.max_rays_per_wavelength = 2'000'000;
        const auto volumetric = solve_rte_spectrum(stack, r);
        const auto biospec = solve_biospec(stack, r);
        for (std::size_t w = 0; w < 3; ++w) {
            const auto& a = volumetric.wavelengths[w].reflectance;
            const auto& b = biospec.wavelengths[w].reflectance;
            INFO(name << " at " << r.wavelengths[w] << " nm: volumetric " << a.value << " +- " << a.stderr << ", BioSpec " << b.value << " +- " << b.stderr);
            CHECK(std::abs(a.value - b.value) < 3.0 * std::hypot(a.stderr, b.stderr) + 0.003);
        }
    }
}

// Matched at normal incidence only: at 60 deg the two walks part, and the volumetric walk states by how much (its
// stated error, from adding-doubling of both descriptions), checked here against the BioSpec walk itself.
TEST_CASE("the volumetric walk on the derived description states its miss of the BioSpec model at the request's incidence", "[matched_volumetric]") {
    SolverRequest r;
    r.spectral.wavelengths = WavelengthGrid::list({420.0, 560.0, 690.0});
    r.spectral.stderr_target = 0.002;
    const auto normal = solve_spectrum(find_solver("rte"), load_material("biospec-lightly"), r);
    REQUIRE(normal.stated_error);
    CHECK(normal.stated_error->R < 1e-3);
    r.spectral.incidence_deg = 60.0;
    const auto volumetric = solve_spectrum(find_solver("rte"), load_material("biospec-lightly"), r);
    const auto biospec = solve_spectrum(find_solver("biospec"), load_material("biospec-lightly"), r);
    REQUIRE(volumetric.stated_error);
    CHECK_THAT(*volumetric.stated_error->meaning, Catch::Contains("biospec-adding-doubling"));
    const double stated = volumetric.stated_error->R;
    double largest = 0.0, sigma = 0.0;
    for (std::size_t w = 0; w < 3; ++w) {
        const auto& a = volumetric.wavelengths[w].reflectance;
        const auto& b = biospec.wavelengths[w].reflectance;
        INFO(r.spectral.wavelengths[w] << " nm: volumetric " << a.value << " +- " << a.stderr << ", BioSpec " << b.value << " +- " << b.stderr << ", stated " << stated);
        CHECK(std::abs(a.value - b.value) <= stated + 4.5 * std::hypot(a.stderr, b.stderr));
        if (std::abs(a.value - b.value) > largest) {
            largest = std::abs(a.value - b.value);
            sigma = std::hypot(a.stderr, b.stderr);
        }
    }
    // Not a loose bound: the largest difference the walks find is the stated one, within their noise and the two
    // 16-channel solves' quadrature (~0.005).
    CHECK(stated > 0.01);
    CHECK(largest >= stated - 4.5 * sigma - 0.005);
}

// Its defining property at the channels of the match, where the thin layers must help (heavily pigmented skin in the
// red) included; a continuous description there: the thin layers' factor grows steadily, and the dermal factor is
// where R_d is least (the least change of the thin layers that lets a dermal factor reach) and moves smoothly with the
// wavelength (before, the thin factor located to 1/256 of its range moved it by up to 26 % between 680 and 690 nm).
TEST_CASE("adding-doubling on the derived description has the BioSpec model's diffuse reflectance", "[matched_volumetric]") {
    const auto stack = matched("biospec-heavily");
    const AdOptions ad{matched_volumetric_channels, false};
    double previous_scale = 0.0, previous_dermal = 0.0;
    for (const double nm : {600.0, 640.0, 650.0, 660.0, 670.0, 680.0, 690.0, 700.0}) {
        const auto tables = [&] {
            auto own = stack;
            own.model.volumetric_matched_to_biospec = false;
            return rte_stack_from(own, nm);
        }();
        const auto m = match_volumetric_to_biospec(stack, tables, nm);
        const double target = solve_biospec_adding_doubling(stack, nm, 0.0, BiospecAdOptions{ad, FoldIntoSkin::drop, std::nullopt}).totals.diffuse_reflectance;
        INFO(nm << " nm: thin-layer factor " << m.thin_scale << ", dermal factor " << m.dermal_scale);
        CHECK(m.residual == 0.0);
        CHECK(solve_adding_doubling(m.stack, AdIncidence{}, ad).diffuse_reflectance == Approx(target).margin(1e-6));
        CHECK(m.thin_scale >= previous_scale);  // grows steadily where the dermis alone cannot match
        if (m.thin_scale > 1.0) {
            const auto dermal_scaled = [&](double factor) {
                auto s = m.stack;
                for (std::size_t k = 2; k < s.layers.size(); ++k) s.layers[k].mu_s_per_cm *= factor;  // papillary, reticular
                return solve_adding_doubling(s, AdIncidence{}, ad).diffuse_reflectance;
            };
            CHECK(dermal_scaled(1.02) >= target - 1e-7);
            CHECK(dermal_scaled(1.0 / 1.02) >= target - 1e-7);
            if (previous_dermal > 0.0) CHECK(std::abs(std::log(m.dermal_scale / previous_dermal)) < 0.05);
            previous_dermal = m.dermal_scale;
        }
        previous_scale = m.thin_scale;
    }
    CHECK(previous_scale > 1.0);
}

TEST_CASE("a derived description makes the absorbers separate the volumetric walk's traced paths", "[matched_volumetric]") {
    const auto light = [](bool derived, const char* melanin) {
        return std::get<LayerStack>(load_material("biospec-lightly", {parse_override(std::string("epidermis.melanosome_fraction=") + melanin),
                                                                      parse_override(std::string("model.volumetric_matched_to_biospec=") + (derived ? "true" : "false"))}));
    };
    for (const auto paths : {TracedPaths::biospec, TracedPaths::volumetric}) {
        CHECK(path_key(light(false, "0.02"), paths) == path_key(light(false, "0.2"), paths));
    }
    // The BioSpec walk does not read the derived description: its paths are still shared.
    CHECK(path_key(light(true, "0.02"), TracedPaths::biospec) == path_key(light(true, "0.2"), TracedPaths::biospec));
    CHECK_FALSE(path_key(light(true, "0.02"), TracedPaths::volumetric) == path_key(light(true, "0.2"), TracedPaths::volumetric));
    CHECK(path_difference(light(true, "0.02"), light(true, "0.2"), TracedPaths::volumetric) == "epidermis.melanosome_fraction");
}

TEST_CASE("a derived description is refused where it cannot be derived, naming the switch", "[matched_volumetric]") {
    auto thin_only = matched("biospec-lightly");
    thin_only.layers.resize(2);
    CHECK_THROWS_WITH(rte_stack_from(thin_only, 550.0), Catch::Contains("model.volumetric_matched_to_biospec = true needs a dermal layer"));
    const auto authors = matched("biospec-lightly", {parse_override("model.swapped_upward_indices=true")});
    CHECK_THROWS_WITH(rte_stack_from(authors, 550.0), Catch::Contains("model.volumetric_matched_to_biospec = true matches biospec-adding-doubling") &&
                                                           Catch::Contains("swapped_upward_indices"));
}
