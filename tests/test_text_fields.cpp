#include <catch2/catch.hpp>

#include "spectral/text_fields.hpp"

using namespace skinspec;

TEST_CASE("parse_double accepts whole numbers only", "[text_fields]") {
    CHECK(parse_double(" 1.5 ") == 1.5);
    CHECK(parse_double("+2e-3") == 2e-3);
    CHECK_FALSE(parse_double("1.5x").has_value());
    CHECK_FALSE(parse_double("").has_value());
    CHECK_FALSE(parse_double("abc").has_value());
}

TEST_CASE("split_fields splits on commas, else on blanks", "[text_fields]") {
    const auto csv = split_fields("400, 0.5 ,x");
    REQUIRE(csv.size() == 3);
    CHECK(csv[1] == "0.5");
    CHECK(csv[2] == "x");
    const auto blanks = split_fields("  400\t0.5  ");
    REQUIRE(blanks.size() == 2);
    CHECK(blanks[0] == "400");
    CHECK(split_fields("400,").size() == 2);
}
