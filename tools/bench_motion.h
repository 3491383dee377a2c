// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `lmk bench --motion` (issue #60): the time to check the PR2 right arm's straight joint lines and
// to plan around a box where they touch it.

#include <string>

#include "lmk/pr2/pr2_motion_check.h"

namespace lmk::cli {

struct MotionBenchOptions {
  int scenes = 30;
  MotionCheckSettings check;
  std::string json;  ///< also write the figures as JSON here, when set
};

/// Runs the scenes, prints the figures (progress on stderr), writes the JSON; an exit code.
int run_motion_bench(const MotionBenchOptions& options);

}  // namespace lmk::cli
