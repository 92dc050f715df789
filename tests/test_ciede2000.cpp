#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "spectral/ciede2000.hpp"

using namespace skinspec;

TEST_CASE("CIEDE2000 reproduces all 34 pairs of Sharma, Wu & Dalal 2005 Table 1", "[ciede2000]") {
    std::ifstream in(SKINSPEC_TEST_REFERENCE_DIR "/ciede2000_sharma2005.txt");
    REQUIRE(in);
    std::string line;
    int pairs = 0;
    Lab first;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#' || line.rfind("pair", 0) == 0) continue;
        std::istringstream row(line);
        int pair = 0, i = 0;
        Lab lab;
        row >> pair >> i >> lab.L >> lab.a >> lab.b;
        double ignored = 0.0, expected = 0.0;
        for (int k = 0; k < 10; ++k) row >> ignored;
        row >> expected;
        REQUIRE(row);
        if (i == 1) {
            first = lab;
            continue;
        }
        INFO("pair " << pair);
        CHECK(ciede2000(first, lab) == Approx(expected).margin(1e-4));
        CHECK(ciede2000(lab, first) == Approx(expected).margin(1e-4));  // symmetric
        ++pairs;
    }
    CHECK(pairs == 34);
}

TEST_CASE("CIEDE2000 of identical colours is zero", "[ciede2000]") {
    CHECK(ciede2000(Lab{50, 10, -10}, Lab{50, 10, -10}) == 0.0);
    CHECK(ciede2000(Lab{0, 0, 0}, Lab{0, 0, 0}) == 0.0);
}
