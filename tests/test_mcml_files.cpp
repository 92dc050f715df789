#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "formats/mcml_files.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

std::filesystem::path write_temp(const char* name, const std::string& text) {
    const auto p = std::filesystem::temp_directory_path() / name;
    std::ofstream(p) << text;
    return p;
}

const std::string good = "1.0 # version\n1\nout.mco A\n1000\n0.01 0.02\n10 20 5\n2\n1.0\n1.37 1 100 0.9 0.1\n1.4 2 10 0 0.2 # layer 2\n1.0\n";

}  // namespace

TEST_CASE("the shipped sample .mci reads as MCML's three-layer sample", "[mcml_files]") {
    const auto runs = read_mci(data_file("mcml/sample.mci"));
    REQUIRE(runs.size() == 1);
    CHECK(runs[0].output_file == "sample.mco");
    CHECK(runs[0].stack.layers.size() == 3);
    CHECK(runs[0].stack.layers[2].mu_a_per_cm == 2.0);
    CHECK(runs[0].grid.na == 30);
}

TEST_CASE(".mci fields, comments and several runs", "[mcml_files]") {
    const auto runs = read_mci(write_temp("ok.mci", good));
    REQUIRE(runs.size() == 1);
    CHECK(runs[0].grid.dr_cm == 0.02);
    CHECK(runs[0].stack.layers[1].refractive_index == 1.4);
    CHECK(runs[0].stack.layers[0].phase.g == 0.9);
}

TEST_CASE("malformed .mci files name file, line, field and range", "[mcml_files]") {
    auto bad = [&](const char* name, std::string from, std::string to) {
        auto text = good;
        text.replace(text.find(from), from.size(), to);
        return write_temp(name, text);
    };
    CHECK_THROWS_WITH(read_mci(bad("v.mci", "1.0 # version", "2.0")), Catch::Contains("v.mci:1: field 'file version' = 2.0 is outside [1, 1]"));
    CHECK_THROWS_WITH(read_mci(bad("mua.mci", "1.37 1 100", "1.37 -1 100")), Catch::Contains("mua.mci:9: field 'layer 1 mua [1/cm]' = -1 is outside [0, inf]"));
    CHECK_THROWS_WITH(read_mci(bad("g.mci", "100 0.9", "100 1.9")), Catch::Contains("field 'layer 1 g' = 1.9 is outside [-1, 1]"));
    CHECK_THROWS_WITH(read_mci(bad("short.mci", "1.4 2 10 0 0.2", "1.4 2 10")), Catch::Contains("short.mci:10: expected layer 2: n mua mus g d"));
    CHECK_THROWS_WITH(read_mci(bad("photons.mci", "1000\n", "1e3.5\n")), Catch::Contains("No. of photons"));
    CHECK_THROWS_WITH(read_mci(bad("fmt.mci", "out.mco A", "out.mco C")), Catch::Contains("field 'format' = C is not allowed"));
    CHECK_THROWS_WITH(read_mci(write_temp("early.mci", good.substr(0, good.size() - 4))), Catch::Contains("ends early"));
    CHECK_THROWS_WITH(read_mci("/nonexistent.mci"), Catch::Contains(".mci file not found"));
}

TEST_CASE(".mco text has MCML's sections in MCML's order", "[mcml_files]") {
    const auto runs = read_mci(write_temp("ok2.mci", good));
    RteRequest r;
    r.stack = runs[0].stack;
    r.photons = 2000;
    r.grid = runs[0].grid;
    const auto text = mco_text(runs[0], solve_rte(r), "test");
    std::size_t at = 0;
    for (const char* section : {"A1 ", "InParm", "RAT", "#Specular reflectance [-]", "#Diffuse reflectance [-]", "#Absorbed fraction [-]",
                                "#Transmittance [-]", "A_l #", "A_z #", "Rd_r #", "Rd_a #", "Tt_r #", "Tt_a #", "\nA_rz\n", "\nRd_ra\n",
                                "\nTt_ra\n"}) {
        const auto found = text.find(section, at);
        INFO(section);
        REQUIRE(found != std::string::npos);
        at = found;
    }
}
