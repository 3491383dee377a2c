// SPDX-License-Identifier: BSD-3-Clause
// Atomic writes: the target is always the old file or the new one, errors name the target and
// their real reason, and temporaries of killed writers do not outlive the next write.

#include "lmk/geometry/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <fstream>

#include "lmk/geometry/error.h"
#include "tests/support/kill_loop.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// A process id that no process holds: a child's, once it has exited and been reaped.
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

using test::error_of;

TEST(AtomicFile, WritingOntoADirectorySaysSo) {
  test::ScratchDir dir;
  fs::create_directory(dir.path() / "target.json");
  const std::string message =
      error_of([&] { write_text_atomically(dir.path() / "target.json", "{}"); });
  EXPECT_NE(message.find("target.json: cannot write: it is a directory"), std::string::npos)
      << message;
  EXPECT_EQ(test::temporaries_in(dir.path()), 0u);
}

TEST(AtomicFile, AWritersErrorNamesTheTargetNotTheTemporary) {
  test::ScratchDir dir;
  const fs::path target = dir.path() / "landmark.lmk";
  const std::string message = error_of([&] {
    write_file_atomically(target, [](const fs::path& tmp) {
      throw Error(tmp.string() + ": cannot open for writing");
    });
  });
  EXPECT_EQ(message, target.string() + ": cannot open for writing");
  EXPECT_EQ(test::temporaries_in(dir.path()), 0u);
}

TEST(AtomicFile, TheNextWriteRemovesTheTemporariesOfDeadWritersOnly) {
  test::ScratchDir dir;
  const fs::path target = dir.path() / "program.json";
  const fs::path stale = dir.path() / (".program.tmp" + std::to_string(dead_pid()) + "-0.json");
  const fs::path live = dir.path() / (".program.tmp" + std::to_string(::getppid()) + "-3.json");
  const fs::path other = dir.path() / (".other.tmp" + std::to_string(dead_pid()) + "-0.json");
  for (const fs::path& p : {stale, live, other}) std::ofstream(p) << "partial";
  write_text_atomically(target, "{\"steps\": []}");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));   // a writer still running may finish
  EXPECT_TRUE(fs::exists(other));  // another target's
  EXPECT_EQ(test::read_bytes(target), "{\"steps\": []}");
}

// A child rewrites a 2 MB target in a loop and is killed with SIGKILL at a random moment, 50
// times: the target always holds one of the two contents whole, and after the next write no
// temporary is left. (tests/crash_safety kills each of lmk's writers the same way.)
TEST(AtomicFile, ASigkilledWriterLeavesTheOldFileOrTheNewOne) {
  test::ScratchDir dir;
  const fs::path target = dir.path() / "scene.pcd";
  const std::array<std::string, 2> contents = {std::string(2 << 20, 'a'),
                                               std::string(2 << 20, 'b')};
  const auto write = [&](int version) { write_text_atomically(target, contents[version]); };
  test::expect_crash_safe(test::kill_writer_repeatedly(write, [&] {
    const std::string now = test::read_bytes(target);
    if (now == contents[0]) return 0;
    if (now == contents[1]) return 1;
    throw Error("the target holds " + std::to_string(now.size()) + " bytes of neither");
  }));
  write(0);
  EXPECT_EQ(test::temporaries_in(dir.path()), 0u);
  EXPECT_EQ(test::read_bytes(target), contents[0]);
}

// The kill loop itself (tests/support/kill_loop.h): a writer that rewrites its target in place,
// truncating it first, is caught, so the loop's kills do land inside writes; the same loop finds
// nothing wrong with write_text_atomically above.
TEST(KillLoop, CatchesAWriterThatRewritesInPlace) {
  test::ScratchDir dir;
  const fs::path target = dir.path() / "scene.pcd";
  const std::array<std::string, 2> contents = {std::string(2 << 20, 'a'),
                                               std::string(2 << 20, 'b')};
  const auto write = [&](int version) {
    std::ofstream out(target, std::ios::binary | std::ios::trunc);
    for (std::size_t at = 0; at < contents[version].size(); at += 4096) {
      out.write(contents[version].data() + at, 4096);
      out.flush();
    }
  };
  const test::KillLoopOutcome outcome = test::kill_writer_repeatedly(write, [&] {
    const std::string now = test::read_bytes(target);
    if (now == contents[0]) return 0;
    if (now == contents[1]) return 1;
    throw Error("the target holds " + std::to_string(now.size()) + " bytes of neither");
  });
  EXPECT_EQ(outcome.runs, 50);
  EXPECT_FALSE(outcome.broken.empty()) << "50 kills of an in-place writer, none caught it";
}

}  // namespace
}  // namespace lmk
