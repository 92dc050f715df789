#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "formats/scene_export.hpp"
#include "materials/material_file.hpp"
#include "scratch_folder.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/wavelength_grid.hpp"

using namespace skinspec;

TEST_CASE("an export states what the renderer's phase functions change in R: nothing when it takes them as they are", "[scene_export]") {
    const auto folder = testing::scratch_folder();
    const std::vector<double> nm{400.0, 550.0, 700.0};
    // HG in every layer, the same g at every wavelength: pbrt-v4 takes the description as it is, so the media's R is
    // the description's (the same adding-doubling on the same numbers).
    const auto hg = std::get<LayerStack>(load_material(
        "biospec-moderately", {{"model.volumetric_matched_to_biospec", "false"}, {"stratum_corneum.volumetric_phase", "henyey_greenstein"}, {"stratum_corneum.volumetric_g", "0.9"},
                               {"epidermis.volumetric_phase", "henyey_greenstein"}, {"epidermis.volumetric_g", "0.85"}}));
    const auto exact = export_scene(hg, MediaRequest{nm, false, 550.0, PhaseExport::hg}, SceneRenderer::pbrt, folder / "hg.pbrt", true);
    CHECK(std::abs(exact.phase_error.largest_R_difference) < 1e-12);

    // The measured profiles as HG of their mean cosine at 550 nm: a difference of about 0.01 (issue 37 measured +0.008
    // at 550 nm in pbrt-v4 itself), stated at one of the exported wavelengths.
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto approximated = export_scene(stack, MediaRequest{nm, false, 550.0, PhaseExport::hg}, SceneRenderer::pbrt, folder / "measured.pbrt", true);
    CHECK(std::abs(approximated.phase_error.largest_R_difference) > 1e-3);
    CHECK(std::abs(approximated.phase_error.largest_R_difference) < 0.03);
    CHECK(std::find(nm.begin(), nm.end(), approximated.phase_error.at_nm) != nm.end());
    // One difference per exported wavelength; the largest is the one stated.
    const auto& per_nm = approximated.phase_error.R_differences;
    REQUIRE(per_nm.size() == nm.size());
    const auto at = std::find(nm.begin(), nm.end(), approximated.phase_error.at_nm) - nm.begin();
    CHECK(per_nm[at] == approximated.phase_error.largest_R_difference);
    for (const double d : per_nm) CHECK(std::abs(d) <= std::abs(approximated.phase_error.largest_R_difference));
    // Mitsuba takes the profiles as tables at 550 nm, their scattering keeping each wavelength's reduced scattering.
    const auto tables = export_scene(stack, MediaRequest{nm}, SceneRenderer::mitsuba, folder / "measured.xml", true);
    CHECK(std::abs(tables.phase_error.largest_R_difference) < 0.002);
    std::filesystem::remove_all(folder);
}

TEST_CASE("an export states how far its volumetric description is from the BioSpec one, as the two walks find it", "[scene_export]") {
    const auto folder = testing::scratch_folder();
    const std::vector<double> nm{450.0, 600.0};
    // The preset's own volumetric description (the Salomatina mu_s', HG): not the BioSpec model's skin.
    const std::vector<MaterialOverride> own{{"model.volumetric_matched_to_biospec", "false"}};
    const auto stack = std::get<LayerStack>(load_material("biospec-lightly", own));
    const auto exported = export_scene(stack, MediaRequest{nm}, SceneRenderer::mitsuba, folder / "gap.xml", true);
    REQUIRE(exported.description_gap);
    const auto& gap = *exported.description_gap;
    REQUIRE(gap.R_differences.size() == nm.size());
    CHECK(!gap.delta_e2000);  // two wavelengths make no colour
    // Independently: each description by its own Monte Carlo walk (the volumetric walk, the BioSpec walk).
    SolverRequest request;
    request.spectral.wavelengths = WavelengthGrid::list(nm);
    request.spectral.stderr_target = 0.001;
    const auto volumetric = solve_spectrum(find_solver("rte"), stack, request);
    const auto biospec = solve_spectrum(find_solver("biospec"), stack, request);
    for (std::size_t i = 0; i < nm.size(); ++i) {
        const auto& v = volumetric.wavelengths[i].reflectance;
        const auto& b = biospec.wavelengths[i].reflectance;
        CHECK(std::abs((v.value - b.value) - gap.R_differences[i]) < 4.5 * std::hypot(v.stderr, b.stderr) + gap.accuracy);
    }
    // That gap is not small (issue 31): far above the solutions' accuracy.
    CHECK(std::abs(gap.largest_R_difference) > 10.0 * gap.accuracy);
    // The preset as it is: its volumetric description derived from the BioSpec one, matched at normal incidence to 1e-7
    // at 16 channels (matched_volumetric.hpp), so the gap is within the two solutions' accuracy.
    const auto derived = export_scene(std::get<LayerStack>(load_material("biospec-lightly")), MediaRequest{nm}, SceneRenderer::mitsuba, folder / "derived.xml", true);
    REQUIRE(derived.description_gap);
    CHECK(std::abs(derived.description_gap->largest_R_difference) <= derived.description_gap->accuracy);
    // Where the two descriptions are the same skin (no layer scatters: BioSpec crossings by HG with g = 1, no
    // Rayleigh; no volumetric scattering), the gap is 0.
    std::vector<MaterialOverride> clear = own;
    clear.push_back({"model.dermal_rayleigh", "false"});
    for (const char* layer : {"stratum_corneum", "epidermis", "dermis"}) {
        const std::string l = layer;
        for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{{"scattering", "henyey_greenstein"}, {"hg_g", "1"},
                                                                                        {"volumetric_scattering", "power_law"},
                                                                                        {"volumetric_mu_s_per_cm_at_500nm", "0"}}) {
            clear.push_back({l + "." + key, value});
        }
    }
    const auto same = export_scene(std::get<LayerStack>(load_material("biospec-lightly", clear)), MediaRequest{nm}, SceneRenderer::mitsuba,
                                   folder / "same.xml", true);
    REQUIRE(same.description_gap);
    CHECK(std::abs(same.description_gap->largest_R_difference) < 1e-6);
    // The authors'-code variant has no exact BioSpec solution: on the layers' own description nothing is stated, and
    // why; a description derived from it is refused, naming the switch.
    const auto derived_authors = std::get<LayerStack>(load_material("biospec-lightly", {{"model.variant", "biospec-authors-code"}}));
    CHECK_THROWS_WITH(export_scene(derived_authors, MediaRequest{nm}, SceneRenderer::mitsuba, folder / "refused.xml", true),
                      Catch::Contains("model.volumetric_matched_to_biospec = true matches biospec-adding-doubling"));
    CHECK(!std::filesystem::exists(folder / "refused.xml"));
    const auto authors = std::get<LayerStack>(load_material("biospec-lightly", {{"model.variant", "biospec-authors-code"}, own.front()}));
    const auto unstated = export_scene(authors, MediaRequest{nm}, SceneRenderer::mitsuba, folder / "authors.xml", true);
    CHECK(!unstated.description_gap);
    CHECK_THAT(unstated.description_gap_why_not, Catch::Contains("swapped_upward_indices"));
    std::filesystem::remove_all(folder);
}

TEST_CASE("the written scene is lit so that a path tracer reaches the light, and states every pixel's value", "[scene_export]") {
    const auto folder = testing::scratch_folder();
    const auto grid = WavelengthGrid::parse(renderer_sampled_wavelengths, "test");
    const std::vector<double> nm(grid.nm().begin(), grid.nm().end());
    // A lossless layer over the white reflector reflects everything, whatever its index or scattering (energy
    // conservation): every pixel is the white of D65 in sRGB, (1, 1, 1), within the colorimetry's own 3e-4 (D65 and
    // the CIE functions sampled at 10 nm against the 4-decimal sRGB matrix).
    for (const char* index : {"1.0", "1.4"}) {
        const auto lossless = std::get<LayerStack>(load_material(std::string(SKINSPEC_TEST_INPUT_DIR) + "/white_reflector.toml",
                                                                 {{"clear.refractive_index", index},
                                                                  {"clear.volumetric_scattering", "power_law"},
                                                                  {"clear.volumetric_mu_s_per_cm_at_500nm", "50"},
                                                                  {"clear.volumetric_g", "0.8"}}));
        for (const auto renderer : {SceneRenderer::pbrt, SceneRenderer::mitsuba}) {
            const auto scene = folder / (std::string("lossless") + std::string(scene_extension(renderer)));
            const auto exported = export_scene(lossless, MediaRequest{nm, false, 550.0, PhaseExport::hg}, renderer, scene, true);
            REQUIRE(exported.expected_pixel.linear_srgb);
            INFO(to_string(renderer) << ", index " << index);
            for (const double c : *exported.expected_pixel.linear_srgb) CHECK(c == Approx(1.0).margin(3e-4));
            // The light is one a path tracer reaches through specular interfaces: an environment, not a delta light
            // (a distant or directional light rendered black, issue 65); the scene says what its pixels should read.
            std::ifstream in(scene);
            const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            CHECK_THAT(text, Catch::Contains(renderer == SceneRenderer::pbrt ? "LightSource \"infinite\"" : "<emitter type=\"constant\">"));
            CHECK_THAT(text, !Catch::Contains("distant") && !Catch::Contains("directional"));
            CHECK_THAT(text, Catch::Contains("every pixel should read linear sRGB "));
        }
    }
    // Media narrower than the renderers' 360-830 nm vanish outside it: no value, and why.
    const auto skin = std::get<LayerStack>(load_material("biospec-lightly"));
    const auto narrow = export_scene(skin, MediaRequest{{400.0, 550.0, 700.0}}, SceneRenderer::mitsuba, folder / "narrow.xml", true);
    CHECK(!narrow.expected_pixel.linear_srgb);
    CHECK_THAT(narrow.expected_pixel.why_not, Catch::Contains("the media cover 400-700 nm"));
    std::filesystem::remove_all(folder);
}
