// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The fixtures of the command line's end-to-end tests (cli_test.cpp, cli_eval_test.cpp,
// cli_serve_test.cpp): the real binary run through the shell in a scratch directory.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/test_support.h"

namespace lmk {

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Cli : public ::testing::Test {
 protected:
  // Runs `lmk ARGS` through the shell, capturing stdout and stderr in the scratch directory.
  test::CommandResult lmk(const std::string& args) {
    return test::run_shell(std::string("'") + LMK_BINARY + "' " + args, dir_);
  }

  // A bad-input run: exit code 2 and exactly one line on stderr, starting "lmk: error: ".
  void expect_bad_input(const std::string& args, const std::string& problem) {
    SCOPED_TRACE("lmk " + args);
    const test::CommandResult r = lmk(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.rfind("lmk: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
  }

  std::string path(const std::string& name) { return "'" + dir_.file(name) + "'"; }

  test::ScratchDir dir_;
};

// A rendered scene and a landmark cut from it: the carton of `lmk gen --seed 1`, whose centre,
// size and yaw lmk gen prints, with margins above and around it but none below the table top.
class CliLandmark : public Cli {
 protected:
  void SetUp() override {
    ASSERT_EQ(lmk("gen " + path("scene.pcd") + " --seed 1").exit_code, 0);
    carton_ = "--box-center -0.301 0.236 0.826 --box-rpy 0 0 -156 --box-size 0.11 0.11 0.21";
  }
  std::string carton_;
};

}  // namespace lmk
