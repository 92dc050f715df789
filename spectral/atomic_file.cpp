#include "spectral/atomic_file.hpp"

#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

#include "spectral/input_error.hpp"

namespace skinspec {

void write_atomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path& temporary)>& write) {
    const auto temporary = file.parent_path() / (file.stem().string() + ".partial-" + std::to_string(::getpid()) + file.extension().string());
    try {
        write(temporary);
        std::error_code error;
        std::filesystem::rename(temporary, file, error);
        if (error) throw InputError(file.string() + ": cannot be written (" + error.message() + ")");
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

void write_text_file(const std::filesystem::path& file, const std::string& text, bool overwrite) {
    if (std::filesystem::exists(file) && !overwrite) throw InputError(file.string() + ": exists already (use --overwrite to replace it)");
    write_atomically(file, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        if (!out) throw InputError(file.string() + ": cannot be written");
        out << text;
        out.close();
        if (!out) throw InputError(file.string() + ": write failed");
    });
}

}  // namespace skinspec
