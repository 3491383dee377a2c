// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The distinctiveness check (docs/landmarks.md, "The distinctiveness check"): a landmark is
// searched for in its own capture scene. Any match away from the captured instance means that a
// robot could mistake that place for the landmark, so the user should hear about it while the scene
// is still at hand and can draw a better box (more empty margin, more context).

#include <limits>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/find_landmark.h"

namespace lmk {

struct DistinctivenessReport {
  /// Matches whose box centre lies farther than settings.selection.nms_radius from the captured box
  /// centre, best first. Empty: the landmark is distinctive in its capture scene.
  std::vector<Match> other_instances;
  /// Did the search find the captured instance itself? A landmark that its own scene does not
  /// reproduce is too thin for the search (too few points, a featureless shape).
  bool found_itself = false;
  /// The captured instance's error, in the metric's unit (NaN when not found): what a look-alike's
  /// error is measured against (CaptureFindings::look_alike_ratio).
  double own_error = std::numeric_limits<double>::quiet_NaN();
  FindResult search;  ///< the whole search, for its statistics
};

/// Searches `landmark` in `capture_scene` (the scene it was cut from, in its capture frame),
/// prepared as the capture prepared it: `settings` with the landmark's veil angle and depth
/// smoothing (CaptureSettings), so that the check sees the scene the landmark was cut from.
DistinctivenessReport check_distinctiveness(const PointCloud& capture_scene,
                                            const Landmark& landmark,
                                            const FindSettings& settings = {});

}  // namespace lmk
