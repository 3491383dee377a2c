// SPDX-License-Identifier: BSD-3-Clause
// IK time per target for the PR2 arms: 1000 random reachable targets (FK of random joint vectors
// within limits), each solved from another random seed. Prints the success rate and the median
// and 95th-percentile time per target.
//
//   build/bench/bench_ik [--targets N]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "lmk/geometry/random.h"
#include "lmk/pr2/ik_solver.h"

namespace {}  // namespace

int main(int argc, char** argv) {
  int targets = 1000;
  if (argc == 3 && std::string(argv[1]) == "--targets") targets = std::stoi(argv[2]);
  const lmk::RobotModel pr2 = lmk::RobotModel::pr2();
  lmk::SplitMix64 rng(99);
  std::vector<double> micros;
  int solved = 0;
  for (int t = 0; t < targets; ++t) {
    const lmk::KinematicChain arm =
        pr2.chain("torso_lift_link", t % 2 ? "l_gripper_tool_frame" : "r_gripper_tool_frame");
    const Eigen::Isometry3d target = arm.forward(arm.random_joints(rng));
    const std::vector<double> seed = arm.random_joints(rng);
    const auto start = std::chrono::steady_clock::now();
    const lmk::IkResult r = lmk::solve_ik(arm, target, seed);
    micros.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
    solved += r.success;
  }
  std::sort(micros.begin(), micros.end());
  std::printf("targets      %d (both arms, random reachable poses, random seeds)\n", targets);
  std::printf("solved       %d (%.1f%%)\n", solved, 100.0 * solved / targets);
  std::printf("median       %.1f us per target\n", micros[micros.size() / 2]);
  std::printf("95th pct     %.1f us per target\n", micros[micros.size() * 95 / 100]);
  std::printf("max          %.1f us per target\n", micros.back());
  return 0;
}
