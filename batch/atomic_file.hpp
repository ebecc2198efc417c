#pragma once
// Files that appear whole or not at all: written under a temporary name in the same folder, then
// renamed, so a task killed mid-way (scancel, a node lost) never leaves a half table or marker
// that a resumed run would take for a finished one.

#include <filesystem>
#include <string>

namespace neopipe::batch {

/// A temporary name beside `target` that no other process (host, pid) uses: "<name>.tmp.<host>.<pid>".
std::filesystem::path temporary_path_for(const std::filesystem::path& target);

/// Writes `text` to `target` through a temporary file and a rename. Throws std::runtime_error naming
/// the file when it cannot (the temporary is removed).
void write_file_atomically(const std::filesystem::path& target, const std::string& text);

/// Removes the leftover temporaries of `target` (of tasks killed while writing it).
void remove_stale_temporaries(const std::filesystem::path& target);

}  // namespace neopipe::batch
