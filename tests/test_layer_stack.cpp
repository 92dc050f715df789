#include <catch2/catch.hpp>

#include <cmath>

#include "materials/layer_stack.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

LayerStack preset(const char* name) { return std::get<LayerStack>(load_material(name)); }

}  // namespace

TEST_CASE("optics of every layer come with their units and descriptions", "[layer_stack]") {
    const auto stack = preset("biospec-moderately");
    const auto optics = stack.optics(550.0);
    REQUIRE(optics.size() == 4);
    CHECK(optics[0].thickness_cm == 0.001);
    CHECK(optics[0].refractive_index == 1.55);
    CHECK(optics[0].crossing == CrossingScattering::measured_stratum_corneum);
    CHECK(optics[1].crossing == CrossingScattering::measured_epidermis);
    CHECK(optics[2].crossing == CrossingScattering::rayleigh_cosine);
    CHECK(optics[2].rayleigh_per_cm > 0.0);
    CHECK(optics[0].rayleigh_per_cm == 0.0);
    for (const auto& o : optics) {
        CHECK(o.mu_a_per_cm > 0.0);
        CHECK(o.mu_s_reduced_per_cm.has_value());
        CHECK(o.mu_s_per_cm.has_value());  // from the reduced scattering (volumetric_scattering = from_reduced_scattering)
    }
    CHECK(stack.optics(2, 550.0).mu_a_per_cm == optics[2].mu_a_per_cm);
}

TEST_CASE("measured reduced scattering comes from Salomatina in 1/cm", "[layer_stack]") {
    // salomatina_HY.txt row 400.42421 nm: mu_s' = 4.94648525691597 /mm.
    auto stack = preset("biospec-lightly");
    stack.layers[0].reduced = ReducedScattering{"salomatina_hypodermis", 0.0, 0.0};
    CHECK(*stack.optics(0, 400.42421).mu_s_reduced_per_cm == Approx(49.4648525691597));
    // Power law: a (lambda / 500)^-b.
    stack.layers[0].reduced = ReducedScattering{"", 40.0, 1.5};
    CHECK(*stack.optics(0, 1000.0).mu_s_reduced_per_cm == Approx(40.0 * std::pow(2.0, -1.5)));
}

TEST_CASE("the 2004 variant turns Rayleigh into cosine and drops ln 10 and the baseline", "[layer_stack]") {
    auto stack = preset("biospec-lightly");
    const double corrected = stack.optics(2, 576.0).mu_a_per_cm;
    stack.model = model_variant("biospec-2004", "test");
    const auto o = stack.optics(2, 576.0);
    CHECK(o.crossing == CrossingScattering::cosine);
    CHECK(o.rayleigh_per_cm == 0.0);
    CHECK(o.mu_a_per_cm < corrected / 2.0);
}

TEST_CASE("the dermal Mie part joins the turn test: a (lambda / 500)^-b, off by default, alone without collagen", "[layer_stack]") {
    auto stack = preset("forearm-nist2017-p50");
    const double rayleigh = stack.optics(3, 1600.0).rayleigh_per_cm;
    CHECK(stack.optics(3, 1600.0).mie_reduced_per_cm == 0.0);
    stack.layers[3].mie_reduced_scattering_per_cm_at_500nm = 20.0;
    stack.layers[3].mie_reduced_scattering_power = 0.7;
    const auto o = stack.optics(3, 1600.0);
    CHECK(o.rayleigh_per_cm == rayleigh);
    CHECK(o.mie_reduced_per_cm == Approx(20.0 * std::pow(3.2, -0.7)));
    CHECK(o.turn_per_cm() == Approx(rayleigh + o.mie_reduced_per_cm));
    stack.layers[3].collagen_fibre_fraction = 0.0;
    const auto no_collagen = stack.optics(3, 1600.0);
    CHECK(no_collagen.rayleigh_per_cm == 0.0);
    CHECK(no_collagen.turn_per_cm() == Approx(o.mie_reduced_per_cm));
    stack.model.dermal_rayleigh = false;  // the 2004 model's cosine crossings: no turn test to join (the field is refused)
    CHECK(stack.optics(3, 1600.0).crossing == CrossingScattering::cosine);
    CHECK(stack.optics(3, 1600.0).turn_per_cm() == 0.0);
}

TEST_CASE("volumetric scattering follows its power law", "[layer_stack]") {
    auto stack = preset("biospec-lightly");
    stack.layers[3].volumetric = VolumetricScattering{200.0, 1.0, PhaseFunctionKind::henyey_greenstein, 0.8};
    const auto o = stack.optics(3, 250.0 * 2.0);
    CHECK(*o.mu_s_per_cm == Approx(200.0));
    CHECK(*stack.optics(3, 1000.0).mu_s_per_cm == Approx(100.0));
    CHECK(*o.g == 0.8);
    CHECK(*o.phase == PhaseFunctionKind::henyey_greenstein);
}

TEST_CASE("a measured volumetric phase: g is the profile's mean cosine and mu_s' is kept", "[layer_stack]") {
    const auto stack = preset("biospec-lightly");
    for (const double nm : {400.0, 500.0, 700.0}) {
        for (const std::size_t k : {0u, 1u}) {
            const auto o = stack.optics(k, nm);
            REQUIRE(o.phase_table);
            // Independent: <cos> of the piecewise-linear C(theta), int cos dC = sum_k slope_k (sin theta_k+1 - sin theta_k).
            const auto& profile = k == 0 ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis();
            const auto angles = profile.angles_deg();
            const auto c = profile.cumulative(nm);
            const double rad = 3.14159265358979323846 / 180.0;
            double mean = 0.0;
            for (std::size_t i = 1; i < angles.size(); ++i) {
                const double slope = (c[i] - c[i - 1]) / ((angles[i] - angles[i - 1]) * rad);
                mean += slope * (std::sin(angles[i] * rad) - std::sin(angles[i - 1] * rad));
            }
            mean /= c.back();
            CHECK(*o.g == Approx(mean).margin(2e-5));  // the 1000-entry table against the exact integral
            CHECK(*o.g == o.phase_table->mean_cos());
            // Similarity: mu_s (1 - g) is the layer's reduced scattering (the one the diffusion modes use).
            CHECK(*o.mu_s_per_cm * (1.0 - *o.g) == Approx(*o.mu_s_reduced_per_cm).epsilon(1e-12));
        }
    }
}

TEST_CASE("wavelengths outside a present chromophore's table are errors, not extrapolations", "[layer_stack]") {
    const auto stack = preset("biospec-lightly");
    CHECK_THROWS_WITH(stack.optics(1, 2600.0), Catch::Contains("eumelanin: wavelength 2600 nm"));
    CHECK_THROWS_AS(stack.optics(0, 240.0), InputError);  // the reduced-scattering tables start at 250 nm
}

TEST_CASE("bottom boundary names", "[layer_stack]") {
    CHECK(parse_bottom_boundary("exit", "b") == BottomBoundary::exit);
    CHECK_THROWS_WITH(parse_bottom_boundary("mirror", "bottom.boundary"), Catch::Contains("allowed: diffuse_reflector, hypodermis, exit"));
}

TEST_CASE("sub-stacks keep the named layers in stack order", "[layer_stack]") {
    const auto stack = preset("biospec-lightly");
    const auto sub = stack.sub_stack({"epidermis", "stratum_corneum"});
    REQUIRE(sub.layers.size() == 2);
    CHECK(sub.layers[0].name == "stratum_corneum");
    CHECK(sub.layers[1].name == "epidermis");
    CHECK_THROWS_WITH(stack.sub_stack({"nail"}), Catch::Contains("'nail' is not a layer of 'biospec-lightly' (allowed: stratum_corneum"));
}

TEST_CASE("volumetric scattering from the reduced scattering: mu_s = mu_s' / (1 - g) in every preset layer", "[layer_stack]") {
    // The similarity relation mu_s' = mu_s (1 - g): the volumetric solvers and diffusion see the same mu_s'.
    const auto skin = std::get<LayerStack>(load_material("biospec-moderately"));
    for (std::size_t k = 0; k < skin.layers.size(); ++k) {
        for (const double nm : {400.0, 550.0, 700.0}) {
            const auto o = skin.optics(k, nm, OpticsScope{true, true});
            REQUIRE(o.mu_s_per_cm);
            REQUIRE(o.mu_s_reduced_per_cm);
            CHECK(*o.mu_s_per_cm * (1.0 - *o.g) == Approx(*o.mu_s_reduced_per_cm).epsilon(1e-12));
        }
    }
}

TEST_CASE("reduced scattering reaches 250-2500 nm continuously", "[layer_stack]") {
    // Salomatina's dermis is measured from 369.27 to 1602.09 nm (8.7825 and 1.5857 /mm there, raw rows); outside,
    // power laws meet those end values (scripts/make_data.py).
    const auto stack = preset("biospec-lightly");
    const auto reduced = [&](double nm) { return *stack.optics(3, nm).mu_s_reduced_per_cm; };
    CHECK(reduced(369.27) == Approx(87.825).epsilon(1e-4));
    CHECK(reduced(1602.086756) == Approx(15.857).epsilon(1e-4));
    CHECK(reduced(360.0) / reduced(369.27) == Approx(1.0).margin(0.07));
    CHECK(reduced(1610.0) / reduced(1602.086756) == Approx(1.0).margin(0.01));
    for (const double nm : {250.0, 300.0, 1700.0, 2000.0}) CHECK(reduced(nm) > reduced(nm + 50.0));  // the tails fall
}
