#include "spectral/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>
#include <system_error>
#include <unistd.h>

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"

namespace skinspec {
namespace {

std::mutex claims_mutex;
OutputClaims* current_claims = nullptr;

// The same file however it is named (relative, with ./ or ..).
std::filesystem::path identity(const std::filesystem::path& file) {
    std::error_code ignored;
    return std::filesystem::weakly_canonical(std::filesystem::absolute(file), ignored);
}

// The temporary under the target's name: replacing a regular file, or created exclusively.
void publish(const std::filesystem::path& temporary, const std::filesystem::path& file, bool replace) {
    std::error_code error;
    const auto status = std::filesystem::symlink_status(file, error);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
        throw InputError(file.string() + ": is " + file_kind(status.type()) + "; only a regular file is replaced by an output");
    }
    if (replace) {
        std::filesystem::rename(temporary, file, error);
        if (error) throw InputError(file.string() + ": cannot be written (" + error.message() + ")");
        return;
    }
    if (::link(temporary.c_str(), file.c_str()) == 0) {
        std::filesystem::remove(temporary, error);
        return;
    }
    if (errno == EEXIST) throw InputError(file.string() + ": exists already (it appeared while this command ran; use --overwrite to replace it)");
    // A file system without hard links: the rename, after one more look.
    if (std::filesystem::exists(std::filesystem::symlink_status(file, error))) throw InputError(file.string() + ": exists already (use --overwrite to replace it)");
    std::filesystem::rename(temporary, file, error);
    if (error) throw InputError(file.string() + ": cannot be written (" + error.message() + ")");
}

}  // namespace

OutputClaims::OutputClaims() {
    const std::lock_guard lock(claims_mutex);
    current_claims = this;
}

OutputClaims::~OutputClaims() {
    const std::lock_guard lock(claims_mutex);
    if (current_claims == this) current_claims = nullptr;
}

void OutputClaims::claim(const std::filesystem::path& file, bool overwrite) {
    const std::lock_guard lock(claims_mutex);
    if (!current_claims) return;
    if (!current_claims->claimed_.emplace(identity(file), overwrite).second) {
        throw InputError(file.string() + ": named as two outputs of one command (each output needs a file of its own)");
    }
}

std::optional<bool> OutputClaims::may_replace(const std::filesystem::path& file) {
    const std::lock_guard lock(claims_mutex);
    if (!current_claims) return std::nullopt;
    const auto it = current_claims->claimed_.find(identity(file));
    return it == current_claims->claimed_.end() ? std::nullopt : std::optional(it->second);
}

void write_atomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path& temporary)>& write, bool overwrite) {
    const auto temporary = file.parent_path() / (file.stem().string() + ".partial-" + std::to_string(::getpid()) + file.extension().string());
    try {
        write(temporary);
        publish(temporary, file, OutputClaims::may_replace(file).value_or(overwrite));
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

void write_text_file(const std::filesystem::path& file, const std::string& text, bool overwrite) {
    write_text_file(file, [&](std::ostream& out) { out << text; }, overwrite);
}

void write_text_file(const std::filesystem::path& file, const std::function<void(std::ostream& out)>& write, bool overwrite) {
    const bool replace = OutputClaims::may_replace(file).value_or(overwrite);
    if (std::filesystem::exists(file) && !replace) throw InputError(file.string() + ": exists already (use --overwrite to replace it)");
    write_atomically(
        file,
        [&](const std::filesystem::path& temporary) {
            std::ofstream out(temporary);
            if (!out) throw InputError(file.string() + ": cannot be written");
            write(out);
            out.close();
            if (!out) throw InputError(file.string() + ": write failed");
        },
        replace);
}

}  // namespace skinspec
