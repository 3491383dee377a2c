// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Running one piece of work in a child process, so that a crash inside a library lmk cannot check
// costs the child and not the caller. lmk reads landmark files of formats 1 to 4, which are
// OpenVDB files, this way: behind a valid checksum a forged grid aborted inside libopenvdb, and
// one such file in `lmk serve --landmarks DIR` killed the server (issue #61, finding 2).

#include <functional>
#include <string>

namespace lmk {

/// Runs `work` in a forked child and returns what it returned. When `work` throws lmk::Error, the
/// same message is thrown here; any other exception, a crash (a signal) or an exit without an
/// answer is an lmk::Error starting with `what`. The child shares nothing back but its answer: it
/// ends with _exit(), without running exit handlers or flushing the parent's buffers.
std::string run_in_child(const std::function<std::string()>& work, const std::string& what);

}  // namespace lmk
