#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "formats/mcml_files.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"

using namespace skinspec;
namespace fs = std::filesystem;

namespace {

std::string read_all(const fs::path& file) {
    auto in = open_input_file(file, "test file");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("an input's UTF-8 byte-order mark is skipped, everything else kept", "[input_file]") {
    const auto dir = fs::temp_directory_path() / ("skinspec_input_file_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "marked.csv", std::ios::binary) << "\xEF\xBB\xBFwavelength_nm,R\n550,0.5\n";
    std::ofstream(dir / "plain.csv", std::ios::binary) << "wavelength_nm,R\n550,0.5\n";
    std::ofstream(dir / "short.txt", std::ios::binary) << "ab";
    std::ofstream(dir / "almost.txt", std::ios::binary) << "\xEF\xBBx";
    CHECK(read_all(dir / "marked.csv") == "wavelength_nm,R\n550,0.5\n");
    CHECK(read_all(dir / "plain.csv") == "wavelength_nm,R\n550,0.5\n");
    CHECK(read_all(dir / "short.txt") == "ab");
    CHECK(read_all(dir / "almost.txt") == "\xEF\xBBx");
    // A reader behind it (an .mci, refused before for its first line's invisible character) reads the same runs.
    const std::string sample = [] {
        std::ifstream in(data_file("mcml/sample.mci"), std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }();
    std::ofstream(dir / "marked.mci", std::ios::binary) << "\xEF\xBB\xBF" << sample;
    const auto runs = read_mci((dir / "marked.mci").string());
    REQUIRE(runs.size() == 1);
    CHECK(runs.front().stack.layers.size() == 3);
    CHECK_THROWS_WITH(open_input_file(dir, "test file"), Catch::Contains("is a folder, not a test file"));
    fs::remove_all(dir);
}
