// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The synthetic tabletop the landmark tests search in: L-shaped blocks (a post and an arm, with no
// symmetry that ICP could confuse) on a table, seen by a noiseless half-resolution Kinect, with a
// ball, a can and a flat box as distractors.

#include <Eigen/Geometry>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/sim/mesh.h"

namespace lmk::test_scenes {

constexpr double kTable = 0.7;  ///< height of the table top, m

/// The L-shape, its origin at the bottom centre of the post.
TriangleMesh l_shape();

/// The capture camera: above and in front of the table, looking down at about 48 degrees.
Eigen::Isometry3d capture_camera();

/// `world` on the table, rendered from `camera` by the tests' noiseless half-resolution Kinect.
PointCloud render_on_table(TriangleMesh world, const Eigen::Isometry3d& camera = capture_camera());

/// The table with L-shapes standing at `positions` (on the table top), the distractors when
/// `distractors`, and L-shapes at the `floating` poses; rendered from `camera`.
PointCloud render_scene(const std::vector<Eigen::Vector2d>& positions, bool distractors,
                        const std::vector<Eigen::Isometry3d>& floating = {},
                        const Eigen::Isometry3d& camera = capture_camera());

/// Where the copies stand in the tests' scene.
extern const std::vector<Eigen::Vector2d> kCopies;

/// The L-shape's box: 1.5 cm margins on the sides facing free space, its bottom on the table top.
Box box_at(const Eigen::Vector2d& xy);

}  // namespace lmk::test_scenes
