// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Running one piece of work in a child process, so that a crash inside a library lmk cannot check
// costs the child and not the caller. lmk reads landmark files of formats 1 to 4, which are
// OpenVDB files, this way: behind a valid checksum a forged grid aborted inside libopenvdb, and
// one such file in `lmk serve --landmarks DIR` killed the server (issue #61, finding 2).

#include <cstddef>
#include <functional>
#include <string>

namespace lmk {

/// Runs `work` in a forked child and returns what it returned. When `work` throws lmk::Error, the
/// same message is thrown here; any other exception, a crash (a signal) or an exit without an
/// answer is an lmk::Error starting with `what`. The child shares nothing back but its answer: it
/// ends with _exit(), without running exit handlers or flushing the parent's buffers.
///
/// The child may map at most `extra_memory` bytes of data beyond what it inherited (RLIMIT_DATA):
/// past it, an allocation fails there, not in the machine. Sanitizer builds, whose shadow memory
/// such a limit would starve, leave it unset.
std::string run_in_child(const std::function<std::string()>& work, const std::string& what,
                         std::size_t extra_memory = std::size_t{512} << 20);

/// Whether run_in_child() limits the child's memory: false in sanitizer builds.
bool child_memory_is_limited();

}  // namespace lmk
