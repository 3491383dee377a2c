// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A landmark of several views counts only what the scene's sensor can see of it (capture_views.h).
// From some sides that part no longer fixes the pose: a cup seen from where its handle is hidden
// is a plain cylinder, free to turn about its axis, and it matches any cylinder. Internal.

#include <Eigen/Geometry>

#include "lmk/landmark/landmark.h"
#include "lmk/search/scene_index.h"

namespace lmk::detail {

/// Whether the points of a landmark of several views that the scene's sensor can see at
/// T_scene_capture (turned towards it, inside its image, not behind the landmark's own nearer
/// points) leave the pose free along more directions, within the noise at that range, than the
/// points its demonstration view (the first) measured (slide_check.h); only directions left
/// essentially free count. False for a landmark of one view.
bool shows_too_little_to_fix(const SceneIndex& scene, const Landmark& landmark,
                             const Eigen::Isometry3d& T_scene_capture);

}  // namespace lmk::detail
