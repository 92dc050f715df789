#include "spectral/input_file.hpp"

#include <cerrno>
#include <cstring>

#include <string>
#include <system_error>

#include "spectral/input_error.hpp"

namespace skinspec {

std::string file_kind(std::filesystem::file_type type) {
    switch (type) {
        case std::filesystem::file_type::symlink: return "a symbolic link";
        case std::filesystem::file_type::directory: return "a folder";
        case std::filesystem::file_type::character: return "a character device";
        case std::filesystem::file_type::block: return "a block device";
        case std::filesystem::file_type::fifo: return "a FIFO";
        case std::filesystem::file_type::socket: return "a socket";
        default: return "not a regular file";
    }
}

std::ifstream open_input_file(const std::filesystem::path& file, std::string_view what, std::uintmax_t max_bytes) {
    const std::string name = file.string();
    std::error_code error;
    const auto status = std::filesystem::status(file, error);
    if (!std::filesystem::exists(status)) throw InputError(name + ": " + std::string(what) + " not found");
    if (!std::filesystem::is_regular_file(status)) throw InputError(name + ": is " + file_kind(status.type()) + ", not a " + std::string(what));
    const auto bytes = std::filesystem::file_size(file, error);
    if (!error && bytes > max_bytes) {
        throw InputError(name + ": is " + std::to_string(bytes) + " bytes, more than a " + std::string(what) + " may be (allowed: at most " +
                         std::to_string(max_bytes >> 20) + " MiB)");
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open the " + std::string(what) + " for reading (" + std::strerror(errno) + ")");
    // A UTF-8 byte-order mark (what some editors and spreadsheets write first) is no part of the text: skipped.
    char mark[3] = {};
    in.read(mark, 3);
    if (!(in.gcount() == 3 && mark[0] == '\xEF' && mark[1] == '\xBB' && mark[2] == '\xBF')) {
        in.clear();
        in.seekg(0);
    }
    return in;
}

}  // namespace skinspec
