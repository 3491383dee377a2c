// SPDX-License-Identifier: BSD-3-Clause
// run_in_child: a crash in the work costs the child, not the caller (issue #61, finding 2: a forged
// landmark grid aborted inside libopenvdb and took the server down).
#include "lmk/geometry/child_process.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "lmk/geometry/error.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// The error that running `work` in a child gives, or "" when it gives none.
std::string error_in_child(const std::function<std::string()>& work) {
  return test::error_of([&] { run_in_child(work, "x.lmk: corrupt landmark file"); });
}

TEST(ChildProcess, TheAnswerComesBackWhole) {
  const std::string big(3'000'000, 'z');  // larger than a pipe holds at once
  const std::string with_nul = big + std::string("\n\0end", 5);
  EXPECT_EQ(run_in_child([&] { return with_nul; }, "x"), with_nul);
  EXPECT_EQ(run_in_child([] { return std::string(); }, "x"), "");
}

TEST(ChildProcess, ACrashCostsTheChildNotTheCaller) {
  EXPECT_EQ(error_in_child([]() -> std::string { std::abort(); }),
            "x.lmk: corrupt landmark file: the process reading it crashed (signal 6, Aborted)");
  EXPECT_NE(error_in_child([]() -> std::string {
              std::raise(SIGKILL);  // as the kernel's OOM killer would
              return "";
            }).find("crashed (signal 9"),
            std::string::npos);
  EXPECT_EQ(error_in_child([]() -> std::string { std::_Exit(3); }),
            "x.lmk: corrupt landmark file: the process reading it ended without an answer");
}

// An allocation past the child's allowance fails in the child, and its answer says so.
TEST(ChildProcess, TheChildAllocatesWithinItsAllowance) {
  if (!child_memory_is_limited()) GTEST_SKIP() << "sanitizer builds leave the limit unset";
  const std::string error = error_in_child([]() -> std::string {
    std::vector<char> big(std::size_t{2} << 30, 'x');  // 2 GiB, four times the 512 MiB allowed
    return std::string(1, big.back());
  });
  EXPECT_EQ(error, "x.lmk: corrupt landmark file: std::bad_alloc");
}

TEST(ChildProcess, ErrorsKeepTheirMessage) {
  EXPECT_EQ(
      error_in_child([]() -> std::string { throw Error("x.lmk: the points are not finite"); }),
      "x.lmk: the points are not finite");
  EXPECT_EQ(error_in_child([]() -> std::string { throw std::bad_alloc(); }),
            "x.lmk: corrupt landmark file: std::bad_alloc");
}

}  // namespace
}  // namespace lmk
