// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The first guess of a landmark's box from one clicked point, which the paper's users asked for
// (docs/landmarks.md, "A first guess of the box"): remove the surface the object stands or hangs
// on, take the cluster of points around the click, fit CGAL's oriented bounding box to it, and
// grow it by a margin of empty space, less on any side where another surface comes closer. Both
// capture interfaces use it: lmk_node's RViz box (ros/) and `lmk serve`.

#include <Eigen/Geometry>
#include <optional>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct BoxGuessSettings {
  double search_radius = 0.35;         ///< m: the neighbourhood of the click considered
  double plane_distance = 0.01;        ///< m: RANSAC inlier distance of the supporting plane
  double cluster_tolerance = 0.015;    ///< m: gap that separates the object from its neighbours
  double margin = 0.03;                ///< m of empty space wanted around the object on each side
  std::size_t min_points = 30;         ///< fewest points the object may have
  std::size_t min_plane_points = 200;  ///< a smaller plane is no support
};

struct BoxGuess {
  Box box;         ///< the guess: the object's box grown by the empty margin
  Box object_box;  ///< the object's tight oriented bounding box
  Indices object;  ///< the object's points in the scene
  /// The supporting plane n.x + d = 0 (n unit, pointing to the object's side), if one was found.
  std::optional<Eigen::Vector4d> support;
};

/// Throws lmk::Error naming the first length outside its bounds: search_radius and
/// cluster_tolerance in (0, 3] m, plane_distance in (0, 0.5] m, margin in [0, 0.5] m.
void validate(const BoxGuessSettings& settings);

/// Guesses the box of the object under `clicked` (a point on it, in the scene frame). Throws
/// lmk::Error, saying what to do, when nothing lies near the click, when the click is on the
/// supporting surface itself, or when the object has fewer than settings.min_points points.
BoxGuess guess_box(const PointCloud& scene, const Eigen::Vector3d& clicked,
                   const BoxGuessSettings& settings = {});

}  // namespace lmk
