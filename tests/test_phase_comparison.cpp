#include <catch2/catch.hpp>

#include "studies/phase_study/phase_comparison.hpp"
#include "materials/material_file.hpp"

using namespace skinspec;

TEST_CASE("comparing thin-layer phase functions reports differences with combined errors", "[phase_comparison]") {
    auto stack = std::get<LayerStack>(load_material("biospec-lightly"));
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::range(400.0, 700.0, 50.0);
    request.max_rays_per_wavelength = 20'000;
    const ThinLayerHg hg{[](double) { return 0.9; }, [](double) { return 0.8; }, "test"};
    const auto r = compare_thin_layer_phase(stack, request, hg, ComparedQuantity::reflectance);
    REQUIRE(r.rows.size() == 7);
    for (const auto& row : r.rows) {
        CHECK(row.difference.value == Approx(row.hg.value - row.measured.value));
        CHECK(row.difference.stderr == Approx(std::hypot(row.hg.stderr, row.measured.stderr)));
        CHECK(row.significant == (std::abs(row.difference.value) > 3.0 * row.difference.stderr));
    }
    REQUIRE(r.delta_e00.has_value());
    CHECK(*r.delta_e00_uncertainty > 0.0);

    // Energy-free SC alone, index-matched: all light is transmitted either way, so nothing differs.
    auto sc = stack.sub_stack({"stratum_corneum"});
    sc.layers[0].carotene_g_per_l = 0.0;
    sc.layers[0].water_fraction = 0.0;
    sc.layers[0].refractive_index = 1.0;
    sc.model.baseline_absorption = false;
    sc.bottom = BottomBoundary::exit;
    const auto t = compare_thin_layer_phase(sc, request, hg, ComparedQuantity::transmittance);
    for (const auto& row : t.rows) {
        CHECK(row.measured.value == Approx(1.0));
        CHECK(row.hg.value == Approx(1.0));
        CHECK_FALSE(row.significant);
    }
    CHECK(t.quantity == "T");
}
