#pragma once
// Atomic file writes: write to a temporary file beside the target, then rename it over the target.
// A reader never sees a half-written file, and a failed write leaves the old file untouched.

#include <filesystem>
#include <functional>
#include <string>

namespace lmk {

/// Calls `write(temporary_path)` to produce the file, then renames it to `path`. If `write`
/// throws, the temporary file is removed and the exception propagates. Throws lmk::Error when the
/// target directory does not exist or the rename fails.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` to `path` atomically; throws lmk::Error naming the file when it cannot.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace lmk
