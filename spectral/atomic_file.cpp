#include "spectral/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>
#include <string_view>
#include <system_error>
#include <sys/stat.h>
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

namespace {

// The process's file-creation mask (read once: setting it back at once is the only way to read it).
mode_t creation_mask() {
    static const mode_t mask = [] {
        const mode_t m = ::umask(0);
        ::umask(m);
        return m;
    }();
    return mask;
}

// A temporary sibling of `file` created exclusively under an unpredictable name (mkstemps: O_CREAT | O_EXCL, six
// random characters), so that nothing planted beforehand (a symbolic link at a name another run would use) is
// written through; its permissions as a new file's (0666 less the umask).
std::filesystem::path create_temporary(const std::filesystem::path& file) {
    const std::string extension = file.extension().string();
    std::string name = (file.parent_path() / (file.stem().string() + ".partial-XXXXXX" + extension)).string();
    static_assert(std::string_view(".partial-XXXXXX").size() == temporary_name_extra);
    const int fd = ::mkstemps(name.data(), static_cast<int>(extension.size()));
    if (fd < 0) throw InputError(file.string() + ": cannot be written (no temporary beside it: " + std::strerror(errno) + ")");
    const bool ok = ::fchmod(fd, 0666 & ~creation_mask()) == 0;
    ::close(fd);
    if (!ok) {
        ::unlink(name.c_str());
        throw InputError(file.string() + ": cannot be written (its temporary: " + std::strerror(errno) + ")");
    }
    return name;
}

// Whether `path` is a regular file of this user: what a writer leaves at the temporary's name (some, as OpenEXR's,
// write a new file there rather than into the one created) and what may be published; not a symbolic link or
// anything else put there meanwhile.
// The temporaries being written, by name in static storage a signal handler may read: a slot is claimed (busy),
// filled, then marked live; the handler removes the live ones.
struct TemporarySlot {
    std::atomic<int> state{0};  // 0 free, 1 being filled or emptied, 2 live
    char name[4096] = {};
};
constexpr std::size_t temporary_slots = 16;
TemporarySlot in_progress[temporary_slots];

// The slot now holding `path` (nullptr when every slot is taken or the name is too long to keep).
TemporarySlot* track(const std::filesystem::path& path) {
    const std::string& name = path.native();
    if (name.size() >= sizeof(TemporarySlot::name)) return nullptr;
    for (auto& slot : in_progress) {
        int free = 0;
        if (!slot.state.compare_exchange_strong(free, 1)) continue;
        std::memcpy(slot.name, name.c_str(), name.size() + 1);
        slot.state.store(2);
        return &slot;
    }
    return nullptr;
}

void untrack(TemporarySlot* slot) {
    if (slot) slot->state.store(0);
}

bool own_regular_file(const std::filesystem::path& path) {
    struct stat now {};
    return ::lstat(path.c_str(), &now) == 0 && S_ISREG(now.st_mode) && now.st_uid == ::geteuid();
}

}  // namespace

void remove_temporaries_in_progress() noexcept {
    for (auto& slot : in_progress) {
        if (slot.state.load() == 2) ::unlink(slot.name);
    }
}

void write_atomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path& temporary)>& write, bool overwrite) {
    const auto temporary = create_temporary(file);
    auto* slot = track(temporary);
    // Published or removed, the name is no longer this run's to remove.
    struct Untrack {
        TemporarySlot* slot;
        ~Untrack() { untrack(slot); }
    } const untrack_at_end{slot};
    try {
        write(temporary);
        if (!own_regular_file(temporary)) {
            throw InputError(file.string() + ": its temporary " + temporary.string() +
                             " was replaced while it was written (not a regular file of this user any more); nothing published");
        }
        publish(temporary, file, OutputClaims::may_replace(file).value_or(overwrite));
        // What was published must be that file: a swap between the look and the rename is undone (the name removed,
        // which removes a link, never what it points to).
        if (!own_regular_file(file)) {
            ::unlink(file.c_str());
            throw InputError(file.string() + ": its temporary was replaced while it was published; nothing published");
        }
    } catch (...) {
        // Only a file of this run's is removed (a planted replacement is left, and named above).
        if (own_regular_file(temporary)) {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
        }
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
