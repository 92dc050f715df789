#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("the data folder: SKINSPEC_DATA_DIR, else the default set at run time, else the source tree's", "[data_paths]") {
    const auto source = data_directory();
    REQUIRE(std::filesystem::is_regular_file(source / "ocio" / "config.ocio"));
    const auto elsewhere = std::filesystem::temp_directory_path() / "skinspec-data-paths-test";
    set_default_data_directory(elsewhere);
    CHECK(data_directory() == elsewhere);
    CHECK_THROWS_WITH(data_file("ocio/config.ocio"), Catch::Contains("skinspec-data-paths-test") && Catch::Contains("SKINSPEC_DATA_DIR"));
    ::setenv("SKINSPEC_DATA_DIR", source.c_str(), 1);
    CHECK(data_directory() == source);
    ::unsetenv("SKINSPEC_DATA_DIR");
    set_default_data_directory(source);
    CHECK(data_directory() == source);
}
