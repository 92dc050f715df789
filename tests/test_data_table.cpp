#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("skinspec_test_" + name);
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST_CASE("every generated CIE table reads with its header", "[data_table]") {
    for (const auto* file : {"cie/observer_cie1931_2deg.csv", "cie/observer_cie1964_10deg.csv", "cie/illuminant_d65.csv",
                             "cie/illuminant_d50.csv", "cie/illuminant_a.csv", "cie/illuminant_e.csv"}) {
        const auto table = DataTable::read(data_file(file));
        CHECK(table.metadata("domain_nm") == "360 830");
        CHECK(table.has_metadata("source"));
        CHECK(table.has_metadata("units"));
        CHECK(table.column("wavelength_nm").size() == 471);
    }
}

TEST_CASE("the tables hold the published check values", "[data_table]") {
    // ../shared/data-sources/SOURCES.md: CIE 2-degree ybar(555) = 1.0, xbar(555) = 0.5120501; D65(560) = 100.
    const auto cmf = DataTable::read(data_file("cie/observer_cie1931_2deg.csv"));
    CHECK(cmf.spectrum("ybar", "ybar")(555) == Approx(1.0).margin(1e-12));
    CHECK(cmf.spectrum("xbar", "xbar")(555) == Approx(0.5120501).margin(1e-12));
    CHECK(cmf.outside() == OutOfRangePolicy::zero);
    const auto d65 = DataTable::read(data_file("cie/illuminant_d65.csv"));
    CHECK(d65.spectrum("power", "D65")(560) == Approx(100.0).margin(1e-12));
    CHECK(d65.outside() == OutOfRangePolicy::error);
}

TEST_CASE("malformed data tables name file and line", "[data_table]") {
    const std::string head = "# skinspec-table: 1\n# outside_domain: zero\n";
    CHECK_THROWS_WITH(DataTable::read(write_temp("a.csv", head + "wavelength_nm,v\n400,1\n500,x\n")),
                      Catch::Contains("a.csv:5: field 'v' = 'x' is not a finite number"));
    CHECK_THROWS_WITH(DataTable::read(write_temp("b.csv", head + "wavelength_nm,v\n400,1,2\n")),
                      Catch::Contains("b.csv:4: 3 fields (allowed: 2"));
    CHECK_THROWS_WITH(DataTable::read(write_temp("c.csv", "# skinspec-table: 2\nwavelength_nm,v\n")),
                      Catch::Contains("unsupported skinspec-table version '2'"));
    CHECK_THROWS_WITH(DataTable::read(write_temp("d.csv", "# skinspec-table: 1\nwavelength_nm,v\n1,2\n3,4\n")),
                      Catch::Contains("'# outside_domain: ...' is missing"));
    CHECK_THROWS_WITH(DataTable::read(write_temp("e.csv", head + "nm,v\n1,2\n")), Catch::Contains("allowed: wavelength_nm"));
    CHECK_THROWS_AS(DataTable::read("/nonexistent/table.csv"), InputError);
    const auto ok = DataTable::read(write_temp("f.csv", head + "wavelength_nm,v\n400,1\n500,2\n"));
    CHECK_THROWS_WITH(ok.column("w"), Catch::Contains("no column 'w'"));
}
