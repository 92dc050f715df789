#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <pugixml.hpp>

#include "formats/mitsuba_scene.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "scratch_folder.hpp"

using namespace skinspec;

namespace {

std::filesystem::path scratch(const char* name) { return testing::scratch_folder() / name; }

// Mitsuba stores sigma_t = sigma_a + sigma_s and albedo = sigma_s / sigma_t: back to sigma_a, sigma_s to rounding.
void check_same_media(const RendererMedia& written, const RendererMedia& read) {
    REQUIRE(read.layers.size() == written.layers.size());
    for (std::size_t k = 0; k < written.layers.size(); ++k) {
        const auto& a = written.layers[k];
        const auto& b = read.layers[k];
        CHECK(b.name == a.name);
        CHECK(b.thickness_mm == Approx(a.thickness_mm).epsilon(1e-14));
        CHECK(b.refractive_index == a.refractive_index);
        REQUIRE(b.sigma_a_per_mm.size() == a.sigma_a_per_mm.size());
        for (std::size_t i = 0; i < a.sigma_a_per_mm.size(); ++i) {
            CHECK(b.sigma_a_per_mm[i] == Approx(a.sigma_a_per_mm[i]).epsilon(1e-12));
            CHECK(b.sigma_s_per_mm[i] == Approx(a.sigma_s_per_mm[i]).epsilon(1e-14));
        }
        CHECK(b.phase.kind == a.phase.kind);
        if (a.phase.kind == RendererPhase::Kind::henyey_greenstein) CHECK(b.phase.g == a.phase.g);
        CHECK(b.phase.values == a.phase.values);
    }
    CHECK(read.bottom_reflector == written.bottom_reflector);
    CHECK(read.above_refractive_index == written.above_refractive_index);
}

}  // namespace

TEST_CASE("a Mitsuba 3 scene reads back as the media written (tabulated phases, RGB, exit bottom)", "[mitsuba_scene]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto spectral = renderer_media(stack, MediaRequest{{400.0, 550.0, 700.0}});
    write_mitsuba_scene(spectral, scratch("spectral.xml"));
    const auto back = read_mitsuba_scene(scratch("spectral.xml"));
    check_same_media(spectral, back);
    CHECK(back.wavelengths_nm == spectral.wavelengths_nm);
    for (const auto& f : mitsuba_scene_files(spectral, scratch("spectral.xml"))) CHECK(std::filesystem::exists(f));

    // Mitsuba bounds RGB values to [0, 1] (it throws above) and clamps spectra there in its *_rgb variants: every
    // sigma_t is written at most 1, its peak in the medium's scale.
    for (const auto& l : spectral.layers) {
        const auto [nm, t] = read_spd_file(spectrum_file_path(scratch("spectral.xml"), l.name, "sigma_t"));
        CHECK(*std::max_element(t.begin(), t.end()) == Approx(1.0).epsilon(1e-15));
    }
    const auto rgb = renderer_media(stack, MediaRequest{{650.0, 550.0, 450.0}, true, 550.0, PhaseExport::hg});
    write_mitsuba_scene(rgb, scratch("rgb.xml"));
    check_same_media(rgb, read_mitsuba_scene(scratch("rgb.xml")));
    pugi::xml_document doc;
    REQUIRE(doc.load_file(scratch("rgb.xml").c_str()));
    for (const auto& value : doc.select_nodes("//rgb")) {
        for (const auto part : split_fields(value.node().attribute("value").as_string())) CHECK(*parse_double(part) <= 1.0);
    }

    auto exit = stack;
    exit.bottom = BottomBoundary::exit;
    exit.below_refractive_index = 1.33;
    exit.layers[2].refractive_index = exit.layers[1].refractive_index;  // an index-matched interface: a null BSDF
    const auto open = renderer_media(exit, MediaRequest{{550.0}});
    write_mitsuba_scene(open, scratch("exit.xml"));
    const auto open_back = read_mitsuba_scene(scratch("exit.xml"));
    check_same_media(open, open_back);
    CHECK(open_back.below_refractive_index == 1.33);
    std::filesystem::remove_all(testing::scratch_folder());
}

TEST_CASE("malformed Mitsuba scenes are input errors", "[mitsuba_scene]") {
    std::ofstream(scratch("broken.xml")) << "<scene version=\"3.0.0\"><medium type=\"homogeneous\" id=\"a\">";
    CHECK_THROWS_WITH(read_mitsuba_scene(scratch("broken.xml")), Catch::Contains("broken.xml"));
    std::ofstream(scratch("noscene.xml")) << "<other/>";
    CHECK_THROWS_WITH(read_mitsuba_scene(scratch("noscene.xml")), Catch::Contains("no <scene> element"));
    std::ofstream(scratch("nosigma.xml")) << "<scene><medium type=\"homogeneous\" id=\"a\"><rgb name=\"albedo\" value=\"0.5\"/></medium></scene>";
    CHECK_THROWS_WITH(read_mitsuba_scene(scratch("nosigma.xml")), Catch::Contains("medium a sigma_t is missing"));
    std::ofstream(scratch("phase.xml")) << "<scene><medium type=\"homogeneous\" id=\"a\"><rgb name=\"albedo\" value=\"0.5\"/><rgb name=\"sigma_t\" value=\"1\"/>"
                                           "<phase type=\"rayleigh\"/></medium></scene>";
    CHECK_THROWS_WITH(read_mitsuba_scene(scratch("phase.xml")), Catch::Contains("phase 'rayleigh'"));
    std::ofstream(scratch("noshape.xml")) << "<scene/>";
    CHECK_THROWS_WITH(read_mitsuba_scene(scratch("noshape.xml")), Catch::Contains("no interfaces"));
    std::filesystem::remove_all(testing::scratch_folder());
}
