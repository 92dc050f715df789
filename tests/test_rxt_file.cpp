#include <catch2/catch.hpp>

#include "formats/rxt_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

// A header in iad's layout (its manual, "The header"): sample, slides, beam, standard, spheres, two spheres.
const std::string header = R"(IAD1   # first
1.40   # sample index
1.50   # slides
2.0    # sample [mm]
1.0    # slide [mm]
5.0    # beam [mm]
0.98   # standard
1      # spheres
200 25 12.5 1 0.96
150 20 10 2 0.95
)";

}  // namespace

TEST_CASE("an iad file: header, then a counted legend with wavelengths", "[iad]") {
    const auto f = parse_rxt(header + "2  # M_R, M_T\n#lambda M_R M_T\n500 0.3 0.4\n510 0.31 0.41 # note\n", "a.rxt");
    CHECK(f.setup.sample_index == 1.4);
    CHECK(f.setup.slide_thickness_mm == 1.0);
    CHECK(f.setup.r_standard == 0.98);
    CHECK(f.setup.spheres == 1.0);
    CHECK(f.setup.t_sphere_mm == 150.0);
    CHECK(f.setup.t_wall == 0.95);
    REQUIRE(f.rows.size() == 2);
    CHECK(*f.rows[1].wavelength_nm == 510.0);
    CHECK(*f.rows[1].m_r == 0.31);
    CHECK(*f.rows[1].m_t == 0.41);
    CHECK_FALSE(f.rows[1].m_u.has_value());
    CHECK(f.rows[1].source == "a.rxt:14");
}

TEST_CASE("an iad file: a letter legend sets measurements and setup fields per row", "[iad]") {
    const auto f = parse_rxt(header + "L r t u w g\n600 0.2 0.3 0.01 0.9 0.8\n", "b.rxt");
    REQUIRE(f.rows.size() == 1);
    const auto& r = f.rows[0];
    CHECK(*r.wavelength_nm == 600.0);
    CHECK(*r.m_u == 0.01);
    CHECK(r.setup.r_wall == 0.9);
    CHECK(r.setup.t_wall == 0.9);  // w sets both walls without a W column
    CHECK(r.setup.g == 0.8);
    CHECK(f.setup.g == 0.0);  // the header's setup is untouched
    // A terse file: the count and the rows on one line.
    CHECK(parse_rxt("IAD1 1.34 1.5 1 1 5 .96 1 203.2 25.4 12.7 1 .96 203.2 25.4 12.7 1 .96 2 0.168 0.249 0.162 0.264", "t.rxt").rows.size() == 2);
}

TEST_CASE("an iad file without slides: thickness 0 or index 1 is no slide", "[iad]") {
    auto text = header;
    text.replace(text.find("1.0    # slide"), 3, "0.0");
    CHECK(parse_rxt(text + "1\n0.3\n", "c.rxt").setup.slide_index == 1.0);
}

TEST_CASE("a bad iad file is refused naming file, line and what is wrong", "[iad]") {
    CHECK_THROWS_WITH(parse_rxt("IAD2 1.4", "x.rxt"), Catch::Contains("x.rxt:1: not an iad measurement file"));
    CHECK_THROWS_WITH(parse_rxt("IAD1 1.4 1.5 2", "x.rxt"), Catch::Contains("x.rxt:1: the header ends before slide_thickness_mm"));
    CHECK_THROWS_WITH(parse_rxt(header + "r q\n0.3 8\n", "x.rxt"), Catch::Contains("x.rxt:11: data legend 'rq': column letter 'q' sets iad's quadrature points"));
    CHECK_THROWS_WITH(parse_rxt(header + "r t\n0.3 0.4\n0.5\n", "x.rxt"), Catch::Contains("x.rxt:13: the last row has 1 numbers, the legend 2"));
    CHECK_THROWS_WITH(parse_rxt(header + "r t\n0.3 abc\n", "x.rxt"), Catch::Contains("x.rxt:12: 'abc' is not a number"));
    CHECK_THROWS_WITH(parse_rxt(header + "r n\n0.3 9\n", "x.rxt"), Catch::Contains("x.rxt:12: sample_index = 9 is outside [1, 4]"));
    CHECK_THROWS_WITH(parse_rxt(header + "2\n", "x.rxt"), Catch::Contains("x.rxt: no measurements"));
}
