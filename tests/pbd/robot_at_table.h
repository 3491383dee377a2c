// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The pbd tests' world: the simulated PR2 standing 0.65 m in front of the landmark tests' table
// (tests/landmark/l_shape_scene.h), facing it, and the L-shape it was shown there.

#include <gtest/gtest.h>

#include <vector>

#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark.h"
#include "lmk/pr2/simulated_pr2.h"
#include "tests/landmark/l_shape_scene.h"

namespace lmk::test_scenes {

/// The robot's base in the table's world: the world's +y is the base's +x.
inline const Eigen::Isometry3d kWorldBase = pose_from_xyz_rpy({0, -0.65, 0}, {0, 0, 0.5 * M_PI});

/// The table with L-shapes at `copies` (and the distractors), seen by `camera`, in the base frame.
inline PointCloud scene_in_base(const std::vector<Eigen::Vector2d>& copies, bool distractors,
                                const Eigen::Isometry3d& camera = capture_camera()) {
  return render_scene(copies, distractors, {}, camera).transformed(kWorldBase.inverse());
}

/// The L captured where it was demonstrated, in the base frame, named "l".
inline Landmark demonstrated_l() {
  const Eigen::Vector2d demo(-0.1, -0.15);
  CaptureSettings settings;
  settings.base_frame = true;
  return capture(scene_in_base({demo}, false), box_at(demo).transformed(kWorldBase.inverse()), "l",
                 settings);
}

/// The PR2 with its torso raised 0.25 m, as one reaching down onto a table, configured and active.
inline SimulatedPr2 robot_at_table() {
  SimulatedPr2 r(Pr2Kinematics(RobotModel::pr2(), 0.25));
  EXPECT_TRUE(r.configure().ok());
  EXPECT_TRUE(r.activate().ok());
  return r;
}

}  // namespace lmk::test_scenes
