// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Atomic file writes: write to a temporary file beside the target, then rename it over the target.
// A reader never sees a half-written file, and a failed write leaves the old file untouched.

#include <filesystem>
#include <functional>
#include <string>

namespace lmk {

/// Calls `write(temporary_path)` to produce the file, flushes it to the disk (fsync), then renames
/// it to `path` and flushes the directory. If `write` throws, the temporary file is removed and
/// the exception propagates (an lmk::Error naming the target, not the temporary). Temporaries of
/// `path` left by writers that no longer run (killed before their rename) are removed first; a
/// live writer's are kept. Throws lmk::Error when the target directory does not exist, the target
/// is a directory, or the flush or the rename fails.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` to `path` atomically; throws lmk::Error naming the file when it cannot.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

/// Whether the process `pid` has ended (no process has that id): what it left behind, a temporary
/// or a scratch directory named after it, may go.
bool process_has_ended(long pid);

}  // namespace lmk
