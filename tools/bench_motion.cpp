// SPDX-License-Identifier: BSD-3-Clause
// Each scene: a random start and goal of the right arm within a reaching range, a 12 x 12 x 30 cm
// box at the straight line's middle hand position, kept when neither end touches it. The line is
// checked; where it touches the box, the planner goes around (its budget: MotionCheckSettings).
// The figures are medians and 95th percentiles, and the configurations each plan checked: the
// measure of a plan's work that does not depend on the machine.

#include "tools/bench_motion.h"

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <vector>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/random.h"
#include "lmk/geometry/solid.h"
#include "lmk/geometry/statistics.h"
#include "lmk/geometry/stopwatch.h"
#include "tools/cli_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

const char* const kRight[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint", "r_elbow_flex_joint",
    "r_forearm_roll_joint", "r_wrist_flex_joint",    "r_wrist_roll_joint"};

// A reaching configuration of the right arm: in front of and beside the robot, elbow bent; within
// the joints' limits.
JointValues reaching(SplitMix64& rng) {
  const double lo[] = {-1.4, -0.3, -1.0, -1.6, -1.0, -1.2, -1.0};
  const double hi[] = {0.4, 0.8, 0.8, -0.2, 1.0, -0.1, 1.0};
  JointValues q;
  for (int i = 0; i < 7; ++i) q[kRight[i]] = lo[i] + (hi[i] - lo[i]) * rng.uniform01();
  return q;
}

PointCloud box_at(const Eigen::Vector3d& centre) {
  PointCloud cloud;
  for (const Eigen::Vector3d& p : Solid::box({0.12, 0.12, 0.3}).surface_points(0.01))
    cloud.points.push_back((p + centre).cast<float>());
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  cloud.height = 1;
  return cloud;
}

struct Figures {
  std::vector<double> line_ms, plan_seconds, plan_checks;
  int found = 0, kept = 0;

  // Configurations the plans checked a second, over all of them.
  double checks_per_second() const {
    const double seconds = std::accumulate(plan_seconds.begin(), plan_seconds.end(), 0.0);
    return seconds > 0.0 ? std::accumulate(plan_checks.begin(), plan_checks.end(), 0.0) / seconds
                         : 0.0;
  }
};

// One scene from `rng`, measured into `f`; false when the scene is no test (an end in the box, or
// the line's middle out of reach).
bool measure_scene(SplitMix64& rng, const Pr2Kinematics& kinematics,
                   const std::shared_ptr<const RobotBody>& body, const JointValues& rest,
                   const MotionCheckSettings& settings, Figures& f) {
  const JointValues from = reaching(rng), to = reaching(rng);
  std::vector<double> middle;
  for (const char* j : kRight) middle.push_back(0.5 * (from.at(j) + to.at(j)));
  Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
  if (!kinematics.forward("right_arm", middle, hand).ok()) return false;
  const RobotMotionChecker check(body, std::make_shared<CollisionScene>(box_at(hand.translation())),
                                 kinematics, rest, settings);
  if (check.check_pose(from) || check.check_pose(to)) return false;
  Stopwatch clock;
  const MotionVerdict line = check.check_line(from, to);
  f.line_ms.push_back(1e3 * clock.seconds());
  if (line.free()) return true;
  clock.restart();
  const MotionPlan plan = check.plan_around("right_arm", from, to);
  f.plan_seconds.push_back(clock.seconds());
  f.plan_checks.push_back(static_cast<double>(plan.checks));
  f.found += plan.found;
  return true;
}

nlohmann::json figures_json(const Figures& f, const MotionBenchOptions& o) {
  return {{"scenes", f.kept},
          {"planning_time", o.check.planning_time},
          {"planning_checks", o.check.planning_checks},
          {"line",
           {{"median_ms", percentile(f.line_ms, 0.5)}, {"p95_ms", percentile(f.line_ms, 0.95)}}},
          {"plan",
           {{"lines_touching", f.plan_seconds.size()},
            {"found", f.found},
            {"median_seconds", percentile(f.plan_seconds, 0.5)},
            {"p95_seconds", percentile(f.plan_seconds, 0.95)},
            {"median_checks", percentile(f.plan_checks, 0.5)},
            {"p95_checks", percentile(f.plan_checks, 0.95)},
            {"checks_per_second", f.checks_per_second()}}}};
}

}  // namespace

int run_motion_bench(const MotionBenchOptions& o) {
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.1);
  const std::shared_ptr<const RobotBody> body = pr2_body();
  // The torso a little up, the left arm raised out of the right arm's way.
  const JointValues rest = {
      {"torso_lift_joint", 0.1}, {"l_shoulder_pan_joint", 1.5}, {"l_shoulder_lift_joint", -0.4}};
  SplitMix64 rng(60);
  Figures f;
  {
    ProgressBar progress("motion scenes");
    while (f.kept < o.scenes) {
      if (!measure_scene(rng, kinematics, body, rest, o.check, f)) continue;
      ++f.kept;
      progress.update(static_cast<std::size_t>(f.kept), static_cast<std::size_t>(o.scenes));
    }
  }
  std::printf("scenes        %d (right arm, a box where the line's hand passes half-way)\n",
              f.kept);
  std::printf("check a line  median %.2f ms, 95%% %.2f ms\n", percentile(f.line_ms, 0.5),
              percentile(f.line_ms, 0.95));
  std::printf(
      "plan around   %zu lines touched the box: %d paths found, median %.3f s, 95%% %.3f s\n",
      f.plan_seconds.size(), f.found, percentile(f.plan_seconds, 0.5),
      percentile(f.plan_seconds, 0.95));
  std::printf("              configurations checked: median %.0f, 95%% %.0f, %.0f a second\n",
              percentile(f.plan_checks, 0.5), percentile(f.plan_checks, 0.95),
              f.checks_per_second());
  if (!o.json.empty()) write_text_atomically(o.json, figures_json(f, o).dump(2) + "\n");
  return kOk;
}

}  // namespace lmk::cli
