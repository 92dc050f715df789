#include <catch2/catch.hpp>

#include "transport/rte/rte_model.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("skin presets run in the volumetric walk, a layer without volumetric scattering is refused", "[rte_model]") {
    auto plain = std::get<LayerStack>(load_material("biospec-lightly"));
    plain.layers[0].volumetric.reset();
    CHECK_THROWS_WITH(rte_stack_from(plain, 550.0), Catch::Contains("layer 'stratum_corneum' of 'biospec-lightly' has no volumetric scattering"));
    std::vector<MaterialOverride> o{parse_override("model.volumetric_matched_to_biospec=false")};  // the layers' own description
    for (const char* layer : {"stratum_corneum", "epidermis", "dermis"}) {
        o.push_back({std::string(layer) + ".volumetric_scattering", "power_law"});
        o.push_back({std::string(layer) + ".volumetric_mu_s_per_cm_at_500nm", "200"});
        o.push_back({std::string(layer) + ".volumetric_phase", "henyey_greenstein"});
        o.push_back({std::string(layer) + ".volumetric_g", "0.8"});
    }
    const auto stack = std::get<LayerStack>(load_material("biospec-lightly", o));
    const auto rte = rte_stack_from(stack, 550.0);
    REQUIRE(rte.layers.size() == 4);
    CHECK(rte.bottom_reflector);
    CHECK(rte.layers[1].mu_a_per_cm == Approx(stack.optics(1, 550.0).mu_a_per_cm));
    CHECK(rte.layers[1].mu_s_per_cm == 200.0);
    CHECK(rte.layers[1].phase.g == 0.8);
    RteRequest request;
    request.stack = rte;
    request.photons = 20'000;
    const auto r = solve_rte(request);
    CHECK(r.transmittance.value == 0.0);  // the reflector returns what reaches the bottom
    CHECK(r.specular_reflectance.value + r.diffuse_reflectance.value + r.absorbed.value == Approx(1.0).margin(1e-12));
}

TEST_CASE("boundary modes parse by name, anything else is refused naming the allowed ones", "[rte_model]") {
    CHECK(parse_boundary_mode("random", "--boundaries") == BoundaryMode::random);
    CHECK(parse_boundary_mode("split", "--boundaries") == BoundaryMode::split);
    CHECK(to_string(BoundaryMode::split) == "split");
    CHECK_THROWS_WITH(parse_boundary_mode("fresnel", "boundaries"), "boundaries: 'fresnel' is not a boundary mode (allowed: random, split)");
}
