// SPDX-License-Identifier: BSD-3-Clause
// Task 7 (issue #60, not the paper's): the bins of task 4 with things in the arm's way. The right
// arm starts at the robot's side, hand at about (0.18, -0.79, 0.80) m, and its straight joint line
// to over the recycling bin sweeps the hand forward and in, through about (0.41, -0.59, 0.82) and
// (0.54, -0.37, 0.72): each scenario stands something on that sweep, or above it. A plan that
// checks its motions goes around; one that does not touches it (counted as a contact).

#include "lmk/demos/detail/demo_task_definitions.h"

namespace lmk::detail {

namespace {

// A box standing on the floor at (x, y), `size` its width, depth and height, turned `yaw`.
void add_box(DemoWorld& w, const std::string& id, double x, double y, const Eigen::Vector3d& size,
             double yaw = 0.0) {
  w.add(id, make_clutter_box(size), pose_from_xyz_rpy({x, y, kFloorInBase}, {0, 0, yaw}));
}

}  // namespace

DemoTask obstacles_task() {
  DemoTask t = new_task(7, "obstacles in the way", 0.05, {0.6, 0.0, 0.1});
  add_bins(t.demonstration, Eigen::Vector3d(kBinX, 0.2, 0.0), {kBinX, -0.2, 0.0});
  add_bin_programs(t);
  // Each scenario: the bins (trash, recycling), then what stands in the way.
  const auto scenario = [](std::string name, std::string program, Eigen::Vector3d trash,
                           Eigen::Vector3d recycling) {
    DemoScenario s = new_scenario(std::move(name), std::move(program));
    add_bins(s.world, trash, recycling);
    return s;
  };
  const Eigen::Vector3d left(kBinX, 0.2, 0.0), right(kBinX, -0.2, 0.0);
  const Eigen::Vector3d tall(0.1, 0.1, 0.9);  // a floor lamp's post, a coat stand

  DemoScenario between =
      scenario("a tall box between the arm and the bin", "drop in recycling", left, right);
  add_box(between.world, "post", 0.45, -0.55, tall);
  DemoScenario nearer = scenario("a tall box nearer the robot", "drop in recycling", left, right);
  add_box(nearer.world, "post", 0.36, -0.68, tall);
  DemoScenario beside =
      scenario("a box beside the bin, on the arm's side", "drop in recycling", left, right);
  add_box(beside.world, "crate", 0.56, -0.45, {0.12, 0.12, 0.75});
  DemoScenario two = scenario("two tall boxes", "drop in recycling", left, right);
  add_box(two.world, "post", 0.45, -0.55, tall);
  add_box(two.world, "crate", 0.57, -0.44, {0.12, 0.12, 0.75});
  DemoScenario wide = scenario("a wide carton across the way", "drop in recycling", left, right);
  add_box(wide.world, "carton", 0.46, -0.58, {0.3, 0.08, 0.85}, -0.6);
  DemoScenario swapped = scenario("a tall box, the bins swapped", "drop in trash", right, left);
  add_box(swapped.world, "post", 0.45, -0.55, tall);
  DemoScenario under = scenario("a table over the way", "drop in recycling", left, right);
  under.world.add("table", make_table({0.4, 0.4, 0.9}),
                  pose_from_xyz_rpy({0.56, -0.66, kFloorInBase}, {0, 0, 0}));
  DemoScenario moved = scenario("a tall box, the bins moved", "drop in recycling",
                                Eigen::Vector3d(kBinX + 0.04, 0.22, 0.2),
                                Eigen::Vector3d(kBinX + 0.03, -0.25, -0.3));
  add_box(moved.world, "post", 0.47, -0.60, tall);
  t.scenarios = {between, nearer, beside, two, wide, swapped, under, moved};
  return t;
}

}  // namespace lmk::detail
