#pragma once
// Shared by the libFuzzer targets (docs/STABILITY.md): the fuzzer's bytes as a file with the extension a
// parser expects. Bad input must end in skinspec::InputError; any other exception, crash, hang or sanitizer
// report is a finding.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "spectral/input_error.hpp"

namespace skinspec::fuzz {

// A per-process file in the temporary folder holding `size` bytes, named with `extension`.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    const auto file = std::filesystem::temp_directory_path() / ("skinspec_fuzz_" + std::to_string(::getpid()) + extension);
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return file;
}

// Runs `parse`, accepting InputError (the documented outcome for malformed input) and nothing else.
template <typename F>
void expect_parsed_or_input_error(F&& parse) {
    try {
        parse();
    } catch (const InputError&) {
    }
}

}  // namespace skinspec::fuzz
