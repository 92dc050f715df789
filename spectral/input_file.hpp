#pragma once
// A user's input file opened for reading, with the checks every reader needs first: it exists, it is a regular file
// (a folder, device or FIFO said "not found", and `color /dev/zero` grew without bound), and it is not larger than a
// bound (inputs are read whole or line by line: the bound keeps memory finite).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace skinspec {

// "a folder", "a FIFO", "a symbolic link", ...: what a path that is not a regular file is, for messages (inputs and outputs).
std::string file_kind(std::filesystem::file_type type);

inline constexpr std::uintmax_t max_input_file_bytes = std::uintmax_t{256} << 20;

// InputError "FILE: WHAT not found" / "is a FIFO, not a WHAT" / "is N bytes, more than ... (allowed at most 256 MiB)".
// The stream starts after a UTF-8 byte-order mark when the file begins with one (every reader accepts it).
std::ifstream open_input_file(const std::filesystem::path& file, std::string_view what, std::uintmax_t max_bytes = max_input_file_bytes);

}  // namespace skinspec
