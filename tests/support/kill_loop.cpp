// SPDX-License-Identifier: BSD-3-Clause
#include "tests/support/kill_loop.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <random>

namespace lmk::test {

namespace {

using Clock = std::chrono::steady_clock;

// Says it has started (a byte on `started`), then rewrites the target until it is killed.
[[noreturn]] void write_until_killed(const std::function<void(int)>& write, int started) {
  try {
    const char ready = 1;
    if (::write(started, &ready, 1) != 1) ::_exit(4);
    for (int k = 1;; ++k) write(k % 2);
  } catch (...) {
    ::_exit(3);  // a writer that fails by itself: the parent reports it
  }
}

}  // namespace

KillLoopOutcome kill_writer_repeatedly(const std::function<void(int)>& write,
                                       const std::function<int()>& version_held, int runs,
                                       unsigned seed) {
  const Clock::time_point start = Clock::now();
  write(0);
  const auto one_write =
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start);
  // The delay counts from the moment the child has started, so that how long a fork takes to be
  // scheduled (longer under a sanitizer, or with the other core busy) does not shift the kills.
  const auto max_delay = std::chrono::microseconds(100) + 4 * one_write;

  KillLoopOutcome outcome;
  std::mt19937 random(seed);
  std::uniform_int_distribution<long> delay(0, max_delay.count());
  for (int run = 0; run < runs; ++run) {
    int started[2];
    if (::pipe(started) != 0) {
      outcome.broken.push_back("run " + std::to_string(run) + ": pipe failed");
      break;
    }
    const pid_t writer = ::fork();
    if (writer < 0) {
      outcome.broken.push_back("run " + std::to_string(run) + ": fork failed");
      break;
    }
    if (writer == 0) write_until_killed(write, started[1]);
    char ready = 0;
    const bool child_started = ::read(started[0], &ready, 1) == 1;
    ::close(started[0]);
    ::close(started[1]);
    if (child_started) ::usleep(static_cast<useconds_t>(delay(random)));
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
