// SPDX-License-Identifier: BSD-3-Clause
#include "tests/support/kill_loop.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <new>
#include <random>

namespace lmk::test {

namespace {

using Clock = std::chrono::steady_clock;

// Says it has started (a byte on `progress`), then rewrites the target until it is killed, saying
// after each write that it has finished it (another byte).
[[noreturn]] void write_until_killed(const std::function<void(int)>& write, int progress) {
  try {
    const char byte = 1;
    if (::write(progress, &byte, 1) != 1) ::_exit(4);
    for (int k = 1;; ++k) {
      write(k % 2);
      if (::write(progress, &byte, 1) != 1) ::_exit(4);
    }
  } catch (...) {
    ::_exit(3);  // a writer that fails by itself: the parent reports it
  }
}

// fork() copies only the calling thread. A child forked while TBB's workers live inherits a
// scheduler that still counts them, and its next parallel loop can wait forever for one of them
// (seen: OpenVDB's point partitioner in save_landmark, about one fork in 800, which hung a whole
// CI run). So the workers are joined before each fork, and the child starts a scheduler of its own;
// false when TBB could not join them.
bool join_tbb_workers() {
  tbb::task_scheduler_handle handle{tbb::attach{}};
  return tbb::finalize(handle, std::nothrow);
}

// Reads `count` bytes from `fd`, one at a time; false when the writer closed it first.
bool await_bytes(int fd, int count) {
  for (int i = 0; i < count; ++i) {
    char byte = 0;
    if (::read(fd, &byte, 1) != 1) return false;
  }
  return true;
}

}  // namespace

KillLoopOutcome kill_writer_repeatedly(const std::function<void(int)>& write,
                                       const std::function<int()>& version_held, int runs,
                                       unsigned seed) {
  const Clock::time_point start = Clock::now();
  write(0);
  const auto one_write =
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start);
  // Each kill waits for the child to report 0-3 finished writes, then for a moment within one
  // write: kills land before the first write, inside writes and between them however slowly the
  // child runs (under a sanitizer, beside a busy core), and any kill after an odd number of
  // finished writes finds the new version unless the next write has finished too.
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> finished_writes(0, 3);
  std::uniform_int_distribution<long> within_a_write(0, 100 + one_write.count());

  KillLoopOutcome outcome;
  for (int run = 0; run < runs; ++run) {
    if (!join_tbb_workers()) {
      outcome.broken.push_back("run " + std::to_string(run) +
                               ": TBB's workers could not be joined");
      break;
    }
    int progress[2];
    if (::pipe(progress) != 0) {
      outcome.broken.push_back("run " + std::to_string(run) + ": pipe failed");
      break;
    }
    const pid_t writer = ::fork();
    if (writer < 0) {
      outcome.broken.push_back("run " + std::to_string(run) + ": fork failed");
      break;
    }
    if (writer == 0) {
      ::close(progress[0]);
      write_until_killed(write, progress[1]);
    }
    ::close(progress[1]);  // so that a writer that dies by itself ends the wait below
    const int writes = finished_writes(random);
    const long delay = within_a_write(random);
    if (await_bytes(progress[0], 1 + writes)) ::usleep(static_cast<useconds_t>(delay));
    ::close(progress[0]);
    ::kill(writer, SIGKILL);
    int status = 0;
    ::waitpid(writer, &status, 0);
    ++outcome.runs;
    if (!WIFSIGNALED(status)) {
      outcome.broken.push_back("run " + std::to_string(run) + ": the writer failed by itself");
      continue;
    }
    try {
      const int version = version_held();
      if (version == 0 || version == 1) {
        ++outcome.held[version];
      } else {
        outcome.broken.push_back("run " + std::to_string(run) + ": neither version");
      }
    } catch (const std::exception& e) {
      outcome.broken.push_back("run " + std::to_string(run) + ": " + e.what());
    }
  }
  return outcome;
}

void expect_crash_safe(const KillLoopOutcome& outcome) {
  std::printf("%d kills: the old version %d times, the new %d, broken %zu\n", outcome.runs,
              outcome.held[0], outcome.held[1], outcome.broken.size());
  EXPECT_GE(outcome.runs, 50);
  for (const std::string& problem : outcome.broken) ADD_FAILURE() << problem;
  EXPECT_GT(outcome.held[1], 0) << "no kill found the new version: the writer made no progress";
}

std::size_t temporaries_in(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.front() == '.' && name.find(".tmp") != std::string::npos) ++n;
  }
  return n;
}

}  // namespace lmk::test
