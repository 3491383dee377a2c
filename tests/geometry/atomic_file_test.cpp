// Atomic writes: the target is always the old file or the new one, errors name the target and
// their real reason, and temporaries of killed writers do not outlive the next write.

#include "geometry/atomic_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <random>
#include <sstream>

#include "geometry/error.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t temporaries_in(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".tmp") != std::string::npos) ++n;
  }
  return n;
}

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
  EXPECT_EQ(temporaries_in(dir.path()), 0u);
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
  EXPECT_EQ(temporaries_in(dir.path()), 0u);
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
  EXPECT_EQ(read_all(target), "{\"steps\": []}");
}

// A child rewrites the target in a loop, alternating two contents of 2 MB; it is killed with
// SIGKILL at a random moment, 50 times. Every time, the target holds one of the two contents
// whole, and after the next write no temporary is left.
TEST(AtomicFile, ASigkilledWriterLeavesTheOldFileOrTheNewOne) {
  test::ScratchDir dir;
  const fs::path target = dir.path() / "scene.pcd";
  const std::string first(2 << 20, 'a'), second(2 << 20, 'b');
  write_text_atomically(target, first);
  std::mt19937 random(7);
  for (int run = 0; run < 50; ++run) {
    const pid_t writer = ::fork();
    if (writer == 0) {
      for (int k = 0;; ++k) write_text_atomically(target, k % 2 ? first : second);
    }
    ::usleep(std::uniform_int_distribution<unsigned>(0, 20000)(random));
    ::kill(writer, SIGKILL);
    ::waitpid(writer, nullptr, 0);
    const std::string now = read_all(target);
    EXPECT_TRUE(now == first || now == second) << "run " << run << ": " << now.size() << " bytes";
  }
  write_text_atomically(target, first);
  EXPECT_EQ(temporaries_in(dir.path()), 0u);
  EXPECT_EQ(read_all(target), first);
}

}  // namespace
}  // namespace lmk
