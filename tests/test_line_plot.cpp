#include <catch2/catch.hpp>

#include <filesystem>

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
