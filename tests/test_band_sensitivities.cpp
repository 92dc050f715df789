#include <catch2/catch.hpp>

#include <fstream>

#include "inverse/image_fit/band_sensitivities.hpp"
#include "scratch_folder.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

std::filesystem::path written(const std::string& name, const std::string& text) {
    const auto file = skinspec::testing::scratch_folder() / name;
    std::ofstream(file) << text;
    return file;
}

}  // namespace

TEST_CASE("band sensitivities are read with their names and weigh a spectrum by sensitivity", "[band_sensitivities]") {
    const auto bands = read_band_sensitivities(written("bands.csv", "# a camera\nwavelength_nm,blue,box\n400,1,0\n500,0,1\n600,0,1\n700,0,0\n"));
    CHECK(bands.names == std::vector<std::string>{"blue", "box"});
    CHECK(bands.wavelengths_nm == std::vector<double>{400, 500, 600, 700});
    std::vector<double> nm;
    for (double l = 380; l <= 780; l += 10) nm.push_back(l);
    const auto w = band_weights(bands, nm);
    REQUIRE(w.size() == 2);
    // A spectrum linear in wavelength: each band records it at its sensitivity's centroid on the grid (the blue ramp
    // 400-500 nm sampled every 10 nm: 2365 / 5.5 = 430 nm; the box with linear edges 400-700 nm: 550 nm).
    const auto recorded = [&](const std::vector<double>& weights) {
        double sum = 0.0, total = 0.0;
        for (std::size_t i = 0; i < nm.size(); ++i) {
            sum += weights[i] * (0.1 + 0.001 * (nm[i] - 380.0));
            total += weights[i];
        }
        CHECK(total == Approx(1.0));
        return sum;
    };
    CHECK(recorded(w[0]) == Approx(0.1 + 0.001 * (430.0 - 380.0)).epsilon(1e-12));
    CHECK(recorded(w[1]) == Approx(0.1 + 0.001 * (550.0 - 380.0)).epsilon(1e-12));
}

TEST_CASE("malformed band sensitivities are refused naming the file and line", "[band_sensitivities]") {
    CHECK_THROWS_WITH(read_band_sensitivities(written("a.csv", "nm,a\n400,1\n")), Catch::Contains("a.csv line 1: expected the header wavelength_nm,BAND"));
    CHECK_THROWS_WITH(read_band_sensitivities(written("b.csv", "wavelength_nm,a\n400,1\n400,2\n")),
                      Catch::Contains("b.csv line 3: wavelength 400 nm is not above the previous 400 nm"));
    CHECK_THROWS_WITH(read_band_sensitivities(written("c.csv", "wavelength_nm,a\n400,-1\n500,2\n")), Catch::Contains("line 2: '-1' is not a sensitivity"));
    CHECK_THROWS_WITH(read_band_sensitivities(written("d.csv", "wavelength_nm,a,b\n400,1\n")), Catch::Contains("line 2: 2 fields, the header has 3"));
    CHECK_THROWS_WITH(read_band_sensitivities(written("e.csv", "wavelength_nm,a\n400,1\n")), Catch::Contains("at least 2 rows"));
    CHECK_THROWS_WITH(read_band_sensitivities(skinspec::testing::scratch_folder() / "missing.csv"), Catch::Contains("not found"));
    const auto nir = read_band_sensitivities(written("f.csv", "wavelength_nm,red,nir\n600,1,0\n700,1,0\n850,0,1\n"));
    const std::vector<double> nm{380, 480, 580, 680, 780};
    CHECK_THROWS_WITH(band_weights(nir, nm), Catch::Contains("band nir is sensitive at 850 nm, outside the model's 380-780 nm"));
    const auto none = read_band_sensitivities(written("g.csv", "wavelength_nm,a\n500,0\n600,0\n"));
    CHECK_THROWS_WITH(band_weights(none, nm), Catch::Contains("band a has no sensitivity at the model's wavelengths"));
}
