// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Crash safety of lmk's writers (issue #17, docs/reliability.md): a writer is killed with SIGKILL
// at random moments, and its target must then hold the old contents or the new, whole and valid.

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lmk::test {

/// What a writer killed repeatedly left behind.
struct KillLoopOutcome {
  int runs = 0;
  /// How many kills left the target holding version 0, version 1.
  std::array<int, 2> held{};
  /// "run N: ...", for each kill after which the target held neither version whole, or the
  /// writer failed by itself.
  std::vector<std::string> broken;
};

/// Writes version 0 of a target, then `runs` times: a forked child calls `write(1)`, `write(0)`,
/// `write(1)`, ... until it is killed with SIGKILL, and `version_held()` then says which version
/// the target holds (0 or 1), reading it with lmk's own reader; it throws (any std::exception) when
/// the target holds neither. The child reports each write it finishes through a pipe, and each
/// kill comes after a random 0-3 of them and a random moment within one write (timed on the
/// first), so kills land before, during and between writes whatever the child's speed: waiting
/// for its progress, not for wall time.
KillLoopOutcome kill_writer_repeatedly(const std::function<void(int version)>& write,
                                       const std::function<int()>& version_held, int runs = 50,
                                       unsigned seed = 7);

/// Asserts (gtest) that `outcome` shows a crash-safe writer: no kill left a broken target, and the
/// writer made progress (some kill found the new version), and prints the counts.
void expect_crash_safe(const KillLoopOutcome& outcome);

/// The number of lmk temporaries (".NAME.tmpPID-N.EXT", geometry/atomic_file.h) in `dir`,
/// recursively.
std::size_t temporaries_in(const std::filesystem::path& dir);

}  // namespace lmk::test
