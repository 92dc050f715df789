#pragma once
// Output files appear complete or not at all: the content goes to a temporary sibling (same folder, same
// extension so format-by-extension writers still work) that is renamed over the target only when writing
// succeeded. A failed or interrupted write never leaves a half-written file under the user's name.
#include <filesystem>
#include <functional>
#include <string>

namespace skinspec {

// Calls write(temporary); renames it to `file` on success, removes it (and rethrows) on failure.
void write_atomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path& temporary)>& write);

// `text` as `file`, atomically; InputError when it exists and `overwrite` is false, or it cannot be written.
void write_text_file(const std::filesystem::path& file, const std::string& text, bool overwrite);

}  // namespace skinspec
