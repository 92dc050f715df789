#pragma once
#include <filesystem>
#include <string_view>

namespace skinspec {

// The folder holding skinspec's own data tables: $SKINSPEC_DATA_DIR when set, else the folder given to
// set_default_data_directory (an installed Python package's own copy), else the source tree's data/ folder
// recorded at configure time.
std::filesystem::path data_directory();
// Called once, before any table is read (the Python package at import).
void set_default_data_directory(const std::filesystem::path& folder);

// data_directory() / relative, with an InputError naming the path when the file does not exist.
std::filesystem::path data_file(std::string_view relative);

}  // namespace skinspec
