#include <catch2/catch.hpp>

#include "spectral/input_error.hpp"
#include "spectral/wavelength_grid.hpp"

using namespace skinspec;

TEST_CASE("range grids include both ends", "[wavelength_grid]") {
    const auto g = WavelengthGrid::range(400, 700, 10);
    REQUIRE(g.size() == 31);
    CHECK(g.front() == 400);
    CHECK(g.back() == 700);
    CHECK(WavelengthGrid::range(400, 405, 2).size() == 3);  // 400, 402, 404
    CHECK(WavelengthGrid::range(550, 550, 1).size() == 1);
}

TEST_CASE("grids parse from option text", "[wavelength_grid]") {
    CHECK(WavelengthGrid::parse("400:700:10", "--wavelengths").size() == 31);
    CHECK(WavelengthGrid::parse("550", "--wavelengths").size() == 1);
    const auto list = WavelengthGrid::parse("436,546", "--wavelengths");
    REQUIRE(list.size() == 2);
    CHECK(list[1] == 546);
}

TEST_CASE("bad grids are input errors naming the option", "[wavelength_grid]") {
    CHECK_THROWS_WITH(WavelengthGrid::parse("700:400:10", "--wavelengths"), Catch::Contains("--wavelengths: last 400 nm is below first 700"));
    CHECK_THROWS_WITH(WavelengthGrid::parse("400:700:0", "--wavelengths"), Catch::Contains("step 0 nm"));
    CHECK_THROWS_WITH(WavelengthGrid::parse("400:700", "--wavelengths"), Catch::Contains("FIRST:LAST:STEP"));
    CHECK_THROWS_WITH(WavelengthGrid::parse("500,400", "--wavelengths"), Catch::Contains("strictly increasing"));
    CHECK_THROWS_WITH(WavelengthGrid::parse("x", "--wavelengths"), Catch::Contains("'x' is not a number"));
    CHECK_THROWS_WITH(WavelengthGrid::parse("-5", "--wavelengths"), Catch::Contains("must be finite and > 0"));
    CHECK_THROWS_WITH(WavelengthGrid::parse("400:700:1e-9", "--wavelengths"), Catch::Contains("too many"));
    CHECK_THROWS_AS(WavelengthGrid::parse("nan", "--wavelengths"), InputError);
}
