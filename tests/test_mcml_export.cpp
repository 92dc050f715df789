#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>

#include "formats/mcml_export.hpp"
#include "materials/material_file.hpp"
#include "scratch_folder.hpp"
#include "spectral/input_error.hpp"
#include "transport/rte/rte_model.hpp"

using namespace skinspec;

TEST_CASE("a skin's volumetric description as MCML input reads back as the stack MCML runs", "[mcml_export]") {
    const auto skin = std::get<LayerStack>(load_material("biospec-moderately"));
    McmlExportRequest request;
    request.wavelengths_nm = {550.0, 650.0};
    request.photons = 1000;
    const auto exported = mcml_export(skin, request);
    REQUIRE(exported.runs.size() == 2);
    const auto file = testing::scratch_folder() / "skin.mci";
    std::ofstream(file) << mci_text(exported.runs, {"a comment"});
    const auto runs = read_mci(file);
    REQUIRE(runs.size() == 2);
    for (std::size_t r = 0; r < 2; ++r) {
        const auto own = rte_stack_from(skin, request.wavelengths_nm[r]);
        INFO("run " << r);
        CHECK(runs[r].output_file == (r == 0 ? "skin_550nm.mco" : "skin_650nm.mco"));
        CHECK(runs[r].photons == 1000);
        CHECK(runs[r].grid.dr_cm == Approx(0.001));
        CHECK(runs[r].grid.nr == 500);
        CHECK_FALSE(runs[r].stack.bottom_reflector);
        REQUIRE(runs[r].stack.layers.size() == own.layers.size());
        for (std::size_t k = 0; k < own.layers.size(); ++k) {
            // Six significant digits, as MCML's own files; the phase function by HG of the same mean cosine.
            const auto& a = runs[r].stack.layers[k];
            const auto& b = own.layers[k];
            CHECK(a.mu_a_per_cm == Approx(b.mu_a_per_cm).epsilon(1e-5));
            CHECK(a.mu_s_per_cm == Approx(b.mu_s_per_cm).epsilon(1e-5));
            CHECK(a.thickness_cm == Approx(b.thickness_cm).epsilon(1e-5));
            CHECK(a.phase.g == Approx(b.phase.mean_cosine()).epsilon(1e-5));
        }
    }
    // What could not be held is said: the measured thin-layer phase functions and the reflector.
    CHECK(std::any_of(exported.substitutions.begin(), exported.substitutions.end(), [](const std::string& s) { return s.find("reflector") != std::string::npos; }));
    CHECK(std::any_of(exported.substitutions.begin(), exported.substitutions.end(), [](const std::string& s) { return s.find("tabulated") != std::string::npos; }));
    // Without the reflector less light comes back (adding-doubling of both, each its own solution): in the red, where the
    // dermis is 1.5-3 transport mean free paths deep, much less.
    CHECK(exported.exported_reflectance[1] < exported.own_reflectance[1] - 0.05);
}

TEST_CASE("an MCML export outside its ranges is refused", "[mcml_export]") {
    const auto skin = std::get<LayerStack>(load_material("biospec-moderately"));
    McmlExportRequest request;
    request.ring_mm = 0.0;
    CHECK_THROWS_WITH(mcml_export(skin, request), Catch::Contains("--ring [mm] = 0 is outside (0, 5]"));
    request = {};
    request.reach_mm = 100.0;
    request.ring_mm = 0.0001;
    CHECK_THROWS_WITH(mcml_export(skin, request), Catch::Contains("1e+06 rings is more than 100000"));
    request = {};
    request.wavelengths_nm = {100.0};
    CHECK_THROWS_WITH(mcml_export(skin, request), Catch::Contains("wavelength [nm] = 100 is outside [250, 2500]"));
}
