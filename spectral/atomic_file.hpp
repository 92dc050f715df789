#pragma once
// Output files appear complete or not at all: the content goes to a temporary sibling (same folder, same
// extension so format-by-extension writers still work) that is published under the target's name only when
// writing succeeded. A failed or interrupted write never leaves a half-written file under the user's name.
//
// Publishing never replaces anything but a regular file (a symbolic link, device, FIFO or folder is refused), and
// replaces one only when allowed: a command claims its outputs before any work (OutputClaims, check_output_path),
// with or without --overwrite; an output claimed without it is created exclusively (a hard link, which fails if a
// file of that name appeared meanwhile: another run, the user), so nothing written during the run is lost. A path
// claimed twice in one command (-o same.exr --spectra same.exr) is refused.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>

namespace skinspec {

// The outputs of one command, for as long as it lives (cli/main.cpp holds one around the command); without one
// (the Python module) nothing is claimed and write_text_file's `overwrite` decides.
class OutputClaims {
public:
    OutputClaims();
    ~OutputClaims();
    OutputClaims(const OutputClaims&) = delete;
    OutputClaims& operator=(const OutputClaims&) = delete;

    // InputError when `file` was claimed already in this command.
    static void claim(const std::filesystem::path& file, bool overwrite);
    // Whether the command claimed `file` with overwrite; nullopt when it did not claim it (or there is no command).
    static std::optional<bool> may_replace(const std::filesystem::path& file);

private:
    std::map<std::filesystem::path, bool> claimed_;
};

// What a temporary's name adds to its target's (".partial-" and six random characters before the extension): an
// output's name must leave room for it within the folder's longest name.
inline constexpr std::size_t temporary_name_extra = 15;

// Calls write(temporary), then publishes it as `file` (replacing an existing regular file only when claimed with
// overwrite, or, unclaimed, when `overwrite`); removes the temporary (and rethrows) on failure.
void write_atomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path& temporary)>& write,
                      bool overwrite = true);

// For a process that must exit at once (a second stop signal): removes the temporaries being written now, so that
// nothing half-written stays behind. Async-signal-safe (unlink on names kept in static storage); up to 16 at a time
// are tracked (more are written, but not removed here).
void remove_temporaries_in_progress() noexcept;

// `text` as `file`, atomically; InputError when it exists and may not be replaced, or it cannot be written.
void write_text_file(const std::filesystem::path& file, const std::string& text, bool overwrite);
// The same with the text written by `write` as it is made (a large text is never held whole).
void write_text_file(const std::filesystem::path& file, const std::function<void(std::ostream& out)>& write, bool overwrite);

}  // namespace skinspec
