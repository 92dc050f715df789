#include <catch2/catch.hpp>

#include <string>

#include "spectral/input_error.hpp"
#include "formats/spectrum_csv.hpp"

using namespace skinspec;

namespace {

std::string input(const char* name) { return std::string(SKINSPEC_TEST_INPUT_DIR) + "/" + name; }

}  // namespace

TEST_CASE("a valid spectrum with comments and header reads", "[spectrum_csv]") {
    const auto s = read_spectrum_csv(input("grey18.csv"));
    CHECK(s.wavelengths_nm().size() == 2);
    CHECK(s(550) == Approx(0.18));
    CHECK(s(300) == Approx(0.18));  // hold outside
}

TEST_CASE("every bad spectrum file gets its one-line error", "[spectrum_csv]") {
    struct Case { const char* file; const char* message; };
    for (const auto& c : {Case{"no_such_file.csv", "file not found"},
                          Case{"non_numeric.csv", "non_numeric.csv:3: field 'reflectance' = 'abc' is not a number"},
                          Case{"not_increasing.csv", "not_increasing.csv:4: field 'wavelength_nm' = 550 does not follow 600 nm"},
                          Case{"over_one.csv", "over_one.csv:3: field 'reflectance' = 1.2 is outside [0, 1]"},
                          Case{"negative.csv", "negative.csv:3: field 'reflectance' = -0.1 is outside [0, 1]"},
                          Case{"one_point.csv", "1 data point(s) (allowed: at least 2)"},
                          Case{"empty.csv", "0 data point(s) (allowed: at least 2)"},
                          Case{"short_coverage.csv", "cover 420-650 nm (allowed: must span at least 400-700 nm)"},
                          Case{"nan_value.csv", "nan_value.csv:3: field 'reflectance' = nan is not allowed"},
                          Case{"inf_value.csv", "inf_value.csv:3: field 'reflectance' = inf is not allowed"},
                          Case{"extra_field.csv", "extra_field.csv:2: 3 field(s) (allowed: 2"}}) {
        INFO(c.file);
        CHECK_THROWS_WITH(read_spectrum_csv(input(c.file)), Catch::Contains(c.message));
    }
    CHECK_THROWS_WITH(read_spectrum_csv(SKINSPEC_TEST_INPUT_DIR), Catch::Contains("is a folder"));
}

TEST_CASE("values over one pass when allowed", "[spectrum_csv]") {
    SpectrumFileRules rules;
    rules.allow_over_one = true;
    CHECK(read_spectrum_csv(input("over_one.csv"), rules)(550) == Approx(1.2));
    CHECK_THROWS_WITH(read_spectrum_csv(input("negative.csv"), rules), Catch::Contains("outside [0, inf)"));
}

TEST_CASE("spectrum's own CSV reads by column and material", "[spectrum_csv]") {
    SpectrumFileRules rules;
    rules.material = "skin_b";
    CHECK(read_spectrum_csv(input("spectrum_result.csv"), rules)(400) == Approx(0.20));  // R by default
    rules.column = "T";
    CHECK(read_spectrum_csv(input("spectrum_result.csv"), rules)(700) == Approx(0.04));
    rules.material = "skin_c";
    CHECK_THROWS_WITH(read_spectrum_csv(input("spectrum_result.csv"), rules), Catch::Contains("--material skin_c has no rows (materials: skin_a, skin_b)"));
    CHECK_THROWS_WITH(read_spectrum_csv(input("spectrum_result.csv")), Catch::Contains("the file holds several materials (skin_a, skin_b); choose one with --material"));
    rules.material = "skin_a";
    rules.column = "Q";
    CHECK_THROWS_WITH(read_spectrum_csv(input("spectrum_result.csv"), rules), Catch::Contains("--column Q is not a value column of the file (columns: material, wavelength_nm, R,"));
    rules.column = "R";
    CHECK_THROWS_WITH(read_spectrum_csv(input("grey18.csv"), rules), Catch::Contains("--material skin_a: the file has no material column"));
}
