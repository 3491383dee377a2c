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
#include "lmk/geometry/settings_schema.h"

namespace lmk {

struct BoxGuessSettings {
  double search_radius = 0.35;         ///< m: the neighbourhood of the click considered
  double plane_distance = 0.01;        ///< m: RANSAC inlier distance of the supporting plane
  double cluster_tolerance = 0.015;    ///< m: gap that separates the object from its neighbours
  double margin = 0.03;                ///< m of empty space wanted around the object on each side
  std::size_t min_points = 30;         ///< fewest points the object may have
  std::size_t min_plane_points = 200;  ///< a smaller plane is no support

  /// Each field described once (geometry/settings_schema.h), for validate() and lmk serve's guess.
  /// A box side beyond 3 m is no landmark (CaptureSettings::max_box_side), and a margin or plane
  /// distance beyond half a metre describes no object (issue #34, finding 2).
  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("search_radius", "The neighbourhood of the click considered, m")
              .positive()
              .at_most(3.0),
          s.search_radius);
    visit(SettingInfo("plane_distance", "RANSAC inlier distance of the supporting plane, m")
              .positive()
              .at_most(0.5),
          s.plane_distance);
    visit(SettingInfo("cluster_tolerance", "Gap that separates the object from its neighbours, m")
              .positive()
              .at_most(3.0),
          s.cluster_tolerance);
    visit(SettingInfo("margin", "Empty space wanted around the object on each side, m")
              .within(0.0, 0.5),
          s.margin);
    visit(SettingInfo("min_points", "Fewest points the object may have (1 to a million)")
              .within(1, 1e6),
          s.min_points);
    // A 1080p frame has 2 million points.
    visit(SettingInfo("min_plane_points", "A smaller plane is no support (1 to 10 million)")
              .within(1, 1e7),
          s.min_plane_points);
  }
};

struct BoxGuess {
  Box box;         ///< the guess: the object's box grown by the empty margin
  Box object_box;  ///< the object's tight oriented bounding box
  Indices object;  ///< the object's points in the scene
  /// The supporting plane n.x + d = 0 (n unit, pointing to the object's side), if one was found.
  std::optional<Eigen::Vector4d> support;
};

/// Throws lmk::Error naming the first setting outside its bounds (the description's).
void validate(const BoxGuessSettings& settings);

/// Guesses the box of the object under `clicked` (a point on it, in the scene frame). Throws
/// lmk::Error, saying what to do, when nothing lies near the click, when the click is on the
/// supporting surface itself, or when the object has fewer than settings.min_points points.
BoxGuess guess_box(const PointCloud& scene, const Eigen::Vector3d& clicked,
                   const BoxGuessSettings& settings = {});

}  // namespace lmk
