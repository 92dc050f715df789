#pragma once
// A temporary folder of the running test case (ctest runs the cases in parallel, each removing its own).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

namespace skinspec::testing {

inline std::filesystem::path scratch_folder() {
    auto name = Catch::getResultCapture().getCurrentTestName();
    for (auto& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    const auto folder = std::filesystem::temp_directory_path() / ("skinspec_test_" + name.substr(0, 60));
    std::filesystem::create_directories(folder);
    return folder;
}

}  // namespace skinspec::testing
