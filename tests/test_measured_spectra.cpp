#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "formats/measured_spectra.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

std::filesystem::path write_file(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("skinspec_measured_" + name);
    std::ofstream(path) << text;
    return path;
}

std::string rows(int n, const std::string& extra = "") {
    std::string out = "# comment\nwavelength_nm,a,b\n";
    for (int i = 0; i < n; ++i) out += std::to_string(400 + 10 * i) + ",0.2,0.3\n";
    return out + extra;
}

}  // namespace

TEST_CASE("measured spectra: one column per spectrum under its name", "[measured_spectra]") {
    const auto m = read_measured_spectra(write_file("ok.csv", rows(6)));
    CHECK(m.names == std::vector<std::string>{"a", "b"});
    CHECK(m.wavelength_nm.size() == 6);
    CHECK(m.reflectance[1][5] == 0.3);
    CHECK(m.row_sources.front().ends_with(":3"));
    const auto one = read_measured_spectra(write_file("one.csv", "wavelength_nm R\n400 0.1\n410 0.2\n420 0.2\n430 0.3\n440 0.3\n"));
    CHECK(one.names == std::vector<std::string>{"R"});
}

TEST_CASE("measured spectra: every problem names file, line and column", "[measured_spectra]") {
    const auto fails = [](const std::string& name, const std::string& text, const std::string& message) {
        const auto path = write_file(name, text);
        CHECK_THROWS_WITH(read_measured_spectra(path), Catch::Contains(path.string()) && Catch::Contains(message));
    };
    fails("nan.csv", rows(5, "450,nan,0.2\n"), ":8: column 'a': 'nan' is not a reflectance in [0, 1.5]");
    fails("over.csv", rows(5, "450,0.2,1.6\n"), ":8: column 'b': '1.6' is not a reflectance in [0, 1.5]");
    fails("short.csv", rows(4), "4 wavelengths; a fit needs at least 5");
    fails("order.csv", rows(5, "440,0.2,0.2\n"), ":8: column 'wavelength_nm': 440 does not increase (previous 440)");
    fails("fields.csv", rows(5, "450,0.2\n"), ":8: row has 2 fields, the header 3");
    fails("header.csv", "400,0.1\n", ":1: the header must be 'wavelength_nm' followed by one name per spectrum");
    fails("twice.csv", "wavelength_nm,a,a\n", "column name 'a' is used twice");
    CHECK_THROWS_WITH(read_measured_spectra("/nonexistent/x.csv"), "/nonexistent/x.csv: measured spectra file not found");
}

TEST_CASE("a skinspec result (a sweep's CSV or JSON) is read as one spectrum per member, named after its swept values", "[measured_spectra]") {
    for (const auto* name : {"sweep_two_members.csv", "sweep_two_members.json"}) {
        CAPTURE(name);
        const auto m = read_measured_spectra(std::filesystem::path(SKINSPEC_TEST_INPUT_DIR) / name);
        REQUIRE(m.names.size() == 2);
        CHECK(m.names[0] == "biospec-lightly[epidermis.melanosome_fraction=0.02]");
        CHECK(m.names[1] == "biospec-lightly[epidermis.melanosome_fraction=0.1]");
        CHECK(m.wavelength_nm.size() == m.reflectance[0].size());
        CHECK(m.reflectance[1].size() == m.wavelength_nm.size());
        CHECK(m.row_sources.size() == m.wavelength_nm.size());
        CHECK(m.reflectance[0][10] > m.reflectance[1][10]);  // more melanin, less reflectance
    }
}
