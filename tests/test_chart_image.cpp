#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <sys/stat.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>

#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

std::filesystem::path temp(const std::string& name) { return std::filesystem::temp_directory_path() / name; }

std::array<float, 3> pixel(const OIIO::ImageBuf& buf, int x, int y) {
    std::array<float, 3> p{};
    buf.getpixel(x, y, p.data(), 3);
    return p;
}

}  // namespace

TEST_CASE("the linear EXR carries patches, chromaticities and metadata", "[chart_image]") {
    const auto& cm = ColorManagement::builtin();
    const ChartLayout layout{2, 1, 40, 8};
    const std::vector<RGB> patches{{1.0, 1.0, 1.0}, {0.2, 0.1, 0.05}};
    const auto file = temp("skinspec_chart.exr");
    write_linear_chart(file, layout, patches, "ACEScg", false, {{"skinspec:seed", "7"}}, cm);
    OIIO::ImageBuf buf(file.string());
    REQUIRE(buf.read());
    const auto white = pixel(buf, 8 + 20, 8 + 20);
    CHECK(white[0] == 1.0f);
    CHECK(white[2] == 1.0f);
    const auto second = pixel(buf, 8 + 48 + 20, 8 + 20);
    CHECK(second[1] == Approx(0.1));
    const auto* chroma = buf.spec().find_attribute("chromaticities");
    REQUIRE(chroma);
    const auto* values = static_cast<const float*>(chroma->data());
    CHECK(values[0] == Approx(0.713));   // AP1 red x
    CHECK(values[6] == Approx(0.32168));  // ACES white x
    CHECK(buf.spec().get_string_attribute("skinspec:seed") == "7");
    CHECK(buf.spec().get_string_attribute("colorspace") == "ACEScg");
}

TEST_CASE("the display PNG of white is 255 and matches the direct sRGB conversion", "[chart_image]") {
    const auto& cm = ColorManagement::builtin();
    const ChartLayout layout{2, 1, 60, 8};
    // A skin-like colour: the PNG path (ACEScg -> display sRGB/Standard) equals XYZ -> sRGB directly.
    const XYZ skin{0.27, 0.25, 0.16};
    const XYZ d65 = ColorManagement::reference_white();
    const std::vector<RGB> patches{cm.from_xyz(d65, d65, "ACEScg"), cm.from_xyz(skin, d65, "ACEScg")};
    const auto file = temp("skinspec_chart.png");
    write_display_chart(file, layout, patches, {"white", "skin"}, "ACEScg", "sRGB", "Standard", {}, cm);
    OIIO::ImageBuf buf(file.string());
    REQUIRE(buf.read(0, 0, true, OIIO::TypeDesc::UINT8));
    const auto white = pixel(buf, 8 + 55, 8 + 55);  // bottom-right corner: clear of the label
    CHECK(white[0] == 1.0f);
    CHECK(white[1] == 1.0f);
    CHECK(white[2] == 1.0f);
    const auto direct = cm.from_xyz(skin, d65, "sRGB");
    const auto shown = pixel(buf, 8 + 68 + 55, 8 + 55);
    for (int c = 0; c < 3; ++c) CHECK(shown[c] == Approx(std::round(direct[c] * 255.0) / 255.0).margin(1.0 / 255.0));
}

TEST_CASE("output paths are checked before anything is written", "[chart_image]") {
    const auto existing = temp("skinspec_existing.png");
    std::ofstream(existing) << "keep";
    CHECK_THROWS_WITH(check_output_path(existing, false, {".png"}), Catch::Contains("exists already (use --overwrite"));
    CHECK_NOTHROW(check_output_path(existing, true, {".png"}));
    CHECK_THROWS_WITH(check_output_path("/nonexistent/folder/x.png", false, {".png"}), Catch::Contains("does not exist"));
    CHECK_THROWS_WITH(check_output_path(temp("x.jpg"), false, {".png", ".exr"}), Catch::Contains("'.jpg' is not supported"));
    CHECK_THROWS_WITH(space_chromaticities("CIE-XYZ-D65"), Catch::Contains("has no RGB primaries"));
    if (geteuid() != 0) CHECK_THROWS_WITH(check_output_path("/proc/x.png", false, {".png"}), Catch::Contains("not writable"));
    // Refused before any work (they failed after it: "cannot be written", an internal "File name too long", a folder
    // taken for an existing file): a name without room for its temporary's, and a folder.
    const long longest = pathconf(std::filesystem::temp_directory_path().c_str(), _PC_NAME_MAX);
    REQUIRE(longest > 20);
    const auto long_name = temp(std::string(static_cast<std::size_t>(longest) - 10, 'a') + ".png");
    CHECK_THROWS_WITH(check_output_path(long_name, false, {".png"}), Catch::Contains("more than this folder takes for an output (at most " +
                                                                                  std::to_string(longest - static_cast<long>(temporary_name_extra)) + ")"));
    const auto just_fits = temp(std::string(static_cast<std::size_t>(longest) - temporary_name_extra - 4, 'b') + ".png");
    CHECK_NOTHROW(check_output_path(just_fits, false, {".png"}));
    const auto folder = temp("skinspec_folder_output.png");
    std::filesystem::create_directories(folder);
    CHECK_THROWS_WITH(check_output_path(folder, true, {".png"}), Catch::Contains("is a folder; an output is written to a file"));
    // An input that is no regular file says what it is (it said "image not found").
    CHECK_THROWS_WITH(read_data_image(folder), Catch::Contains("is a folder, not an image"));
    const auto fifo = temp("skinspec_fifo_input.exr");
    std::filesystem::remove(fifo);
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    CHECK_THROWS_WITH(read_data_image(fifo), Catch::Contains("is a FIFO, not an image"));
    std::filesystem::remove(fifo);
    CHECK_THROWS_WITH(read_data_image(temp("skinspec_no_such_image.exr")), Catch::Contains("image not found"));
    std::filesystem::remove(folder);
}

TEST_CASE("a data image rewritten with another size reads back at its new size (fuzz finding)", "[chart_image]") {
    // OIIO's shared image cache used to keep the first spec of a file name: 2 x 2 x 1 cached, 8 x 8 x 3 read into
    // a buffer of the old size (heap overflow under ASan).
    const auto file = std::filesystem::temp_directory_path() / ("skinspec_rewrite_" + std::to_string(::getpid()) + ".exr");
    write_data_image(file, {2, 2, 1, std::vector<float>(4, 0.5f), true, {"Y"}}, {});
    CHECK(read_data_image(file).values.size() == 4);
    write_data_image(file, {8, 8, 3, std::vector<float>(192, 0.25f), true, {"R", "G", "B"}}, {});
    const auto again = read_data_image(file);
    CHECK(again.width == 8);
    CHECK(again.channels == 3);
    CHECK(again.values.size() == 192);
    CHECK(again.values.back() == 0.25f);
    std::filesystem::remove(file);
}

TEST_CASE("a one-row chart's long axis title is wrapped inside the image, not cut at its edge", "[chart_image]") {
    const auto& cm = ColorManagement::builtin();
    const ChartLayout layout{3, 1, 112, 8};
    const std::vector<RGB> patches(3, RGB{0.2, 0.15, 0.1});
    const ChartAxes axes{"epidermis.melanosome_fraction: volume fraction of melanosomes (v_m) (unitless), log spacing", {"0.005", "0.0354", "0.25"}, "", {}};
    const auto file = temp("skinspec_chart_title.png");
    std::filesystem::remove(file);
    write_display_chart(file, layout, patches, {}, "ACEScg", "sRGB", "Standard", {}, cm, axes);
    OIIO::ImageBuf buf(file.string());
    REQUIRE(buf.read(0, 0, true, OIIO::TypeDesc::UINT8));
    const int width = buf.spec().width;
    const auto background = pixel(buf, width - 1, 0);
    // The title needs three lines at this width; the right-most 4 columns of the header stay background.
    const int header_px = 3 * 14 + 14;
    for (int y = 0; y < header_px; ++y) {
        for (int x = width - 4; x < width; ++x) CHECK(pixel(buf, x, y) == background);
    }
    CHECK(buf.spec().height >= 2 * 8 + 112 + 4 * 14);  // room above the patches for three title lines and the values
}
