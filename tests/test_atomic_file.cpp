#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;
namespace fs = std::filesystem;

TEST_CASE("a failed write leaves neither the file nor a temporary, a good one replaces atomically", "[atomic_file]") {
    const auto dir = fs::temp_directory_path() / "skinspec_atomic_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const auto file = dir / "out.csv";
    CHECK_THROWS_AS(write_atomically(file,
                                     [](const fs::path& temporary) {
                                         std::ofstream(temporary) << "half";
                                         throw std::runtime_error("disk full");
                                     }),
                    std::runtime_error);
    CHECK(fs::is_empty(dir));
    write_text_file(file, "first\n", false);
    CHECK_THROWS_WITH(write_text_file(file, "second\n", false), Catch::Contains("exists already (use --overwrite"));
    write_text_file(file, "second\n", true);
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    CHECK(line == "second");
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
    fs::remove_all(dir);
}
