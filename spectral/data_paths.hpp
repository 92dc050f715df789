#pragma once
#include <filesystem>
#include <string_view>

namespace skinspec {

// The folder holding skinspec's own data tables: $SKINSPEC_DATA_DIR when set, else the source tree's
// data/ folder recorded at configure time.
std::filesystem::path data_directory();

// data_directory() / relative, with an InputError naming the path when the file does not exist.
std::filesystem::path data_file(std::string_view relative);

}  // namespace skinspec
