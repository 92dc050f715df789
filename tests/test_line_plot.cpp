#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "spectral/image_files.hpp"
#include "spectral/input_error.hpp"
#include "spectral/line_plot.hpp"

using namespace skinspec;

TEST_CASE("spectrum plots are written as PNG and SVG", "[line_plot]") {
    const PlotCurve curve{"test R", {400, 500, 600, 700}, {0.1, 0.2, 0.4, 0.5}, {0.01, 0.01, 0.01, 0.01}, {0.8, 0.6, 0.5}, false};
    for (const auto* name : {"skinspec_plot.png", "skinspec_plot.svg"}) {
        const auto file = std::filesystem::temp_directory_path() / name;
        std::filesystem::remove(file);
        write_line_plot(file, "title", "Wavelength (nm)", "Reflectance (fraction)", {curve});
        CHECK(std::filesystem::file_size(file) > 1000);
    }
    CHECK_THROWS_WITH(write_line_plot("x.pdf", "t", "x", "y", {curve}), Catch::Contains("allowed: .png, .svg"));
    CHECK_THROWS_AS(write_line_plot("x.png", "t", "x", "y", {}), InputError);
}

TEST_CASE("curves without a band and with negative values (residuals) are drawn", "[line_plot]") {
    const PlotCurve no_band{"measured", {400, 500, 600}, {0.1, 0.3, 0.5}, {}, {0.2, 0.4, 0.7}, true, 1};
    const PlotCurve residual{"residual", {400, 500, 600}, {-0.02, 0.01, 0.005}, {0.002, 0.002, 0.002}, {0.8, 0.3, 0.1}, false, 2};
    const auto file = std::filesystem::temp_directory_path() / "skinspec_plot_residual.svg";
    std::filesystem::remove(file);
    write_line_plot(file, "t", "x", "y", {no_band, residual});
    CHECK(std::filesystem::file_size(file) > 1000);
}

namespace {

// True when no pixel within 3 px of the image's edge is drawn on (the background is white): nothing is cut.
bool edges_blank(const std::filesystem::path& file) {
    const auto image = read_data_image(file);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (x >= 3 && x < image.width - 3 && y >= 3 && y < image.height - 3) continue;
            for (int c = 0; c < std::min(3, image.channels); ++c) {
                if (image.values[(static_cast<std::size_t>(y) * image.width + x) * image.channels + c] < 0.98f) return false;
            }
        }
    }
    return true;
}

std::vector<PlotCurve> many_curves(std::size_t n, const std::string& label_tail) {
    std::vector<PlotCurve> curves;
    for (std::size_t k = 0; k < n; ++k) {
        const auto style = distinct_series_style(k);
        curves.push_back({"subject" + std::to_string(k) + label_tail, {400, 550, 700}, {0.1 + 0.004 * k, 0.3, 0.5}, {}, style.colour, k % 2 == 1, style.marker});
    }
    return curves;
}

}  // namespace

TEST_CASE("the legend lies inside the image for 1 to 120 curves with long labels, listing every k-th past what fits", "[line_plot]") {
    for (const std::size_t n : {1, 6, 18, 40, 80, 120}) {
        for (const auto* tail : {"", " measured, forearm, 2 mm probe, second visit"}) {
            CAPTURE(n, tail);
            const auto file = std::filesystem::temp_directory_path() / "skinspec_plot_legend.png";
            std::filesystem::remove(file);
            const auto layout = write_line_plot(file, "t", "Wavelength (nm)", "R", many_curves(n, tail));
            CHECK(layout.legend_left_px >= 0.0);
            CHECK(layout.legend_right_px <= layout.width_px);
            CHECK(layout.legend_top_px >= 0.0);
            CHECK(layout.legend_bottom_px <= layout.height_px);
            CHECK(layout.legend_entries >= std::min<std::size_t>(n, 12));  // up to 12 entries always fit in full
            if (layout.legend_entries < n) CHECK(layout.legend_entries >= 10);  // the every-k-th list still names several
            CHECK(edges_blank(file));
        }
    }
}

TEST_CASE("a long title or axis label is wrapped into the space it has", "[line_plot]") {
    CHECK(wrap_plot_text("short", 20) == std::vector<std::string>{"short"});
    CHECK(wrap_plot_text("Measured vs HG thin layers; R of the skin", 30) == std::vector<std::string>{"Measured vs HG thin layers;", "R of the skin"});
    const auto halves = wrap_plot_text("Run time in seconds of one run on every core", 30);
    REQUIRE(halves.size() == 2);
    CHECK(halves[0].size() <= 30);
    CHECK(halves[1].size() <= 30);
    const auto file = std::filesystem::temp_directory_path() / "skinspec_plot_wrap.png";
    std::filesystem::remove(file);
    const std::string title = "Measured (solid) vs HG (dashed) thin layers; R of the skin, T of SC + epidermis; bands +-2 s.e.";
    const auto layout = write_line_plot(file, title, std::string(120, 'x'), "R", many_curves(3, ""));
    CHECK(layout.title_lines.size() == 2);
    CHECK(edges_blank(file));
}

TEST_CASE("80 series differ in colour or marker", "[line_plot]") {
    for (std::size_t a = 0; a < 80; ++a) {
        for (std::size_t b = a + 1; b < 80; ++b) {
            const auto s = distinct_series_style(a), t = distinct_series_style(b);
            CHECK((s.colour != t.colour || s.marker != t.marker));
        }
    }
}

TEST_CASE("single-point curves and stacked panels are drawn inside the image", "[line_plot]") {
    const PlotCurve lone{"550 nm", {550}, {0.27}, {0.002}, {0.2, 0.4, 0.7}, false};
    const PlotCurve difference{"difference", {400, 500, 600}, {-0.02, 0.01, 0.005}, {0.002, 0.002, 0.002}, {0.8, 0.3, 0.1}, false, 2};
    const auto file = std::filesystem::temp_directory_path() / "skinspec_plot_panels.png";
    std::filesystem::remove(file);
    const auto layout = write_figure(file, "t", "Wavelength (nm)", {PlotPanel{"R", {lone}, {}, {}}, PlotPanel{"HG - measured", {difference}, {}, {}}});
    CHECK(layout.height_px > 1000);
    CHECK(layout.legend_entries == 2);
    CHECK(edges_blank(file));
}

TEST_CASE("a figure whose curves have no labels has no legend", "[line_plot]") {
    const PlotCurve unlabelled{"", {400, 500, 600}, {0.1, 0.3, 0.5}, {}, {0.2, 0.4, 0.7}, false};
    const auto file = std::filesystem::temp_directory_path() / "skinspec_plot_unlabelled.png";
    std::filesystem::remove(file);
    const auto layout = write_line_plot(file, "t", "x", "y", {unlabelled});
    CHECK(layout.legend_entries == 0);
    CHECK(edges_blank(file));
}
