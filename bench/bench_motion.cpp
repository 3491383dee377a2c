// SPDX-License-Identifier: BSD-3-Clause
// Checked arm motions (issue #60): the time to check a straight joint line of the PR2's right arm,
// and to plan around a box set where that line's hand passes half-way. Each scene: a random start
// and goal within a reaching range, a 12 x 12 x 30 cm box at the line's middle hand position, kept
// when neither end touches it. Prints the median and 95th-percentile times and how many plans were
// found, with the configurations each plan checked (its budget: MotionCheckSettings).
//
//   build/bench/bench_motion [--scenes N] [--planning-time S] [--planning-checks N]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "lmk/geometry/random.h"
#include "lmk/geometry/solid.h"
#include "lmk/pr2/pr2_motion_check.h"

namespace {

const char* const kRight[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint", "r_elbow_flex_joint",
    "r_forearm_roll_joint", "r_wrist_flex_joint",    "r_wrist_roll_joint"};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A reaching configuration of the right arm: in front of and beside the robot, elbow bent; within
// the joints' limits.
lmk::JointValues reaching(lmk::SplitMix64& rng) {
  const double lo[] = {-1.4, -0.3, -1.0, -1.6, -1.0, -1.2, -1.0};
  const double hi[] = {0.4, 0.8, 0.8, -0.2, 1.0, -0.1, 1.0};
  lmk::JointValues q;
  for (int i = 0; i < 7; ++i) q[kRight[i]] = lo[i] + (hi[i] - lo[i]) * rng.uniform01();
  return q;
}

lmk::PointCloud box_at(const Eigen::Vector3d& centre) {
  lmk::PointCloud cloud;
  for (const Eigen::Vector3d& p : lmk::Solid::box({0.12, 0.12, 0.3}).surface_points(0.01))
    cloud.points.push_back((p + centre).cast<float>());
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  cloud.height = 1;
  return cloud;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  int scenes = 30;
  lmk::MotionCheckSettings settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--scenes") {
      scenes = std::stoi(argv[i + 1]);
    } else if (flag == "--planning-time") {
      settings.planning_time = std::stod(argv[i + 1]);
    } else if (flag == "--planning-checks") {
      settings.planning_checks = std::stoul(argv[i + 1]);
    } else {
      std::fprintf(stderr, "bench_motion: unknown option '%s'\n", flag.c_str());
      return 2;
    }
  }
  const lmk::Pr2Kinematics kinematics(lmk::RobotModel::pr2(), 0.1);
  const auto body = lmk::pr2_body();
  const lmk::JointValues rest = {
      {"torso_lift_joint", 0.1}, {"l_shoulder_pan_joint", 1.5}, {"l_shoulder_lift_joint", -0.4}};
  lmk::SplitMix64 rng(60);
  std::vector<double> line_ms, plan_s, plan_checks;
  double all_checks = 0.0, all_seconds = 0.0;
  int found = 0, kept = 0;
  while (kept < scenes) {
    const lmk::JointValues from = reaching(rng), to = reaching(rng);
    lmk::JointValues middle;
    for (const auto& [name, value] : from) middle[name] = 0.5 * (value + to.at(name));
    std::vector<double> q;
    for (const char* j : kRight) q.push_back(middle.at(j));
    Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
    if (!kinematics.forward("right_arm", q, hand).ok()) continue;
    const lmk::RobotMotionChecker check(
        body, std::make_shared<lmk::CollisionScene>(box_at(hand.translation())), kinematics, rest,
        settings);
    if (check.check_pose(from) || check.check_pose(to)) continue;  // an end inside the box
    ++kept;
    auto start = std::chrono::steady_clock::now();
    const lmk::MotionVerdict line = check.check_line(from, to);
    line_ms.push_back(1e3 * seconds_since(start));
    if (line.free()) continue;
    start = std::chrono::steady_clock::now();
    const lmk::MotionPlan plan = check.plan_around("right_arm", from, to);
    plan_s.push_back(seconds_since(start));
    plan_checks.push_back(static_cast<double>(plan.checks));
    all_checks += static_cast<double>(plan.checks);
    all_seconds += plan_s.back();
    found += plan.found;
  }
  std::printf("scenes        %d (right arm, a box where the line's hand passes half-way)\n", kept);
  std::printf("check a line  median %.2f ms, 95%% %.2f ms\n", percentile(line_ms, 0.5),
              percentile(line_ms, 0.95));
  std::printf(
      "plan around   %zu lines touched the box: %d paths found, median %.3f s, 95%% %.3f s\n",
      plan_s.size(), found, percentile(plan_s, 0.5), percentile(plan_s, 0.95));
  std::printf("              configurations checked: median %.0f, 95%% %.0f, %.0f a second\n",
              percentile(plan_checks, 0.5), percentile(plan_checks, 0.95),
              all_seconds > 0.0 ? all_checks / all_seconds : 0.0);
  return 0;
}
