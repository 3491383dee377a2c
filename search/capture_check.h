// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The capture check (issue #59): what a landmark's shape and its capture scene say about how well
// a search can find it, measured once at capture and stored in its file (capture_findings.h).
// It joins the three checks a capture has run since issues #16 and #33: the noise of the capture
// frame and the slide check against it (landmark/shape_check.h), and the look-alike check
// (distinctiveness.h), which searches.

#include <optional>

#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"
#include "lmk/landmark/shape_check.h"
#include "lmk/search/distinctiveness.h"
#include "lmk/search/find_settings.h"

namespace lmk {

struct CaptureCheck : ShapeCheck {
  /// The look-alike check's search; nothing when it was not run (no scene, a flat landmark, or
  /// not asked for).
  std::optional<DistinctivenessReport> look_alikes;
};

/// Checks `landmark` as captured from `capture_scene` (its first view's cloud, in the capture
/// frame): check_shape() with `settings.scene`, then the look-alike check searching with `settings`
/// (FindSettings::scene.up set to the landmark's; progress and threads as the caller wants them)
/// when `look_alikes` is true. Without a scene (null: a file from before format 4) there is no
/// look-alike check; nor for a flat landmark (CaptureSettings::allow_flat), which is meant to slide
/// on its plane.
CaptureCheck check_capture(const Landmark& landmark, const PointCloud* capture_scene,
                           const FindSettings& settings = {}, bool look_alikes = true);

}  // namespace lmk
