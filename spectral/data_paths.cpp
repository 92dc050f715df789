#include "spectral/data_paths.hpp"

#include <cstdlib>

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

std::filesystem::path& default_data_directory() {
    static std::filesystem::path folder(SKINSPEC_DEFAULT_DATA_DIR);
    return folder;
}

}  // namespace

std::filesystem::path data_directory() {
    if (const char* env = std::getenv("SKINSPEC_DATA_DIR"); env != nullptr && *env != '\0') {
        return std::filesystem::path(env);
    }
    return default_data_directory();
}

void set_default_data_directory(const std::filesystem::path& folder) { default_data_directory() = folder; }

std::filesystem::path data_file(std::string_view relative) {
    const auto path = data_directory() / relative;
    if (!std::filesystem::is_regular_file(path)) {
        throw InputError("data file " + path.string() +
                         " not found (set SKINSPEC_DATA_DIR to the folder holding skinspec's data/)");
    }
    return path;
}

}  // namespace skinspec
