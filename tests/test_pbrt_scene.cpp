#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "formats/pbrt_scene.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "scratch_folder.hpp"

using namespace skinspec;

namespace {

std::filesystem::path scratch(const char* name) { return testing::scratch_folder() / name; }

// What pbrt-v4 stores: per layer sigma_a, sigma_s, g, thickness and index (relative eta at each interface).
void check_same_media(const RendererMedia& written, const RendererMedia& read) {
    REQUIRE(read.layers.size() == written.layers.size());
    for (std::size_t k = 0; k < written.layers.size(); ++k) {
        const auto& a = written.layers[k];
        const auto& b = read.layers[k];
        CHECK(b.name == a.name);
        CHECK(b.thickness_mm == Approx(a.thickness_mm).epsilon(1e-14));
        CHECK(b.refractive_index == Approx(a.refractive_index).epsilon(1e-14));
        CHECK(b.sigma_a_per_mm == a.sigma_a_per_mm);
        CHECK(b.sigma_s_per_mm == a.sigma_s_per_mm);
        CHECK(b.phase.g == a.phase.g);
    }
    CHECK(read.bottom_reflector == written.bottom_reflector);
    CHECK(read.rgb == written.rgb);
}

}  // namespace

TEST_CASE("a pbrt-v4 scene reads back as the media written (spectral, RGB, exit bottom)", "[pbrt_scene]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto spectral = renderer_media(stack, MediaRequest{{400.0, 500.0, 600.0, 700.0}, false, 550.0, PhaseExport::hg});
    write_pbrt_scene(spectral, scratch("spectral.pbrt"));
    const auto back = read_pbrt_scene(scratch("spectral.pbrt"));
    check_same_media(spectral, back);
    CHECK(back.wavelengths_nm == spectral.wavelengths_nm);
    CHECK(pbrt_scene_files(spectral, scratch("spectral.pbrt")).size() == 1 + 2 * stack.layers.size());
    // Interfaces are disks (an exact plane test; pbrt's single-precision triangle test missed hits near 2000 mm
    // triangles) and the depth limit is far beyond any path's weight.
    std::stringstream text;
    text << std::ifstream(scratch("spectral.pbrt")).rdbuf();
    CHECK(text.str().find("trianglemesh") == std::string::npos);
    CHECK(text.str().find("Shape \"disk\" \"float height\" [ 0 ] \"float radius\" [ 1000 ]") != std::string::npos);
    CHECK(text.str().find("\"integer maxdepth\" [ 100000 ]") != std::string::npos);
    for (const auto& f : pbrt_scene_files(spectral, scratch("spectral.pbrt"))) CHECK(std::filesystem::exists(f));

    const auto rgb = renderer_media(stack, MediaRequest{{650.0, 550.0, 450.0}, true, 550.0, PhaseExport::hg});
    write_pbrt_scene(rgb, scratch("rgb.pbrt"));
    check_same_media(rgb, read_pbrt_scene(scratch("rgb.pbrt")));
    CHECK(pbrt_scene_files(rgb, scratch("rgb.pbrt")).size() == 1);

    auto exit = stack;
    exit.bottom = BottomBoundary::exit;
    exit.below_refractive_index = 1.33;
    const auto open = renderer_media(exit, MediaRequest{{550.0}, false, 550.0, PhaseExport::hg});
    write_pbrt_scene(open, scratch("exit.pbrt"));
    const auto open_back = read_pbrt_scene(scratch("exit.pbrt"));
    check_same_media(open, open_back);
    CHECK(open_back.below_refractive_index == Approx(1.33).epsilon(1e-14));
    std::filesystem::remove_all(testing::scratch_folder());
}

TEST_CASE("pbrt-v4 refuses tabulated phases, malformed scenes are input errors", "[pbrt_scene]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto own = renderer_media(stack, MediaRequest{{550.0}});
    CHECK_THROWS_WITH(write_pbrt_scene(own, scratch("own.pbrt")), Catch::Contains("pbrt-v4 media take Henyey-Greenstein only"));
    CHECK_FALSE(std::filesystem::exists(scratch("own.pbrt")));
    std::ofstream(scratch("broken.pbrt")) << "MakeNamedMedium \"a\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 1 2";
    CHECK_THROWS_WITH(read_pbrt_scene(scratch("broken.pbrt")), Catch::Contains("unterminated ["));
    std::ofstream(scratch("quote.pbrt")) << "Shape \"trianglemesh";
    CHECK_THROWS_WITH(read_pbrt_scene(scratch("quote.pbrt")), Catch::Contains("unterminated string"));
    std::ofstream(scratch("nomedium.pbrt")) << "AttributeBegin MediumInterface \"x\" \"\" Material \"interface\" Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0]\nAttributeEnd\n"
                                                "AttributeBegin MediumInterface \"\" \"x\" Shape \"trianglemesh\" \"point3 P\" [0 0 -1 1 0 -1 1 1 -1]\nAttributeEnd\n";
    CHECK_THROWS_WITH(read_pbrt_scene(scratch("nomedium.pbrt")), Catch::Contains("unknown medium 'x'"));
    CHECK_THROWS_WITH(read_pbrt_scene(scratch("missing.pbrt")), Catch::Contains("cannot be read"));
    std::filesystem::remove_all(testing::scratch_folder());
}
