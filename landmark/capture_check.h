// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The capture check (issue #59): what a landmark's shape and its capture scene say about how well
// a search can find it, measured once at capture and stored in its file (capture_findings.h).
// It joins the three checks a capture has run since issues #16 and #33: the noise of the capture
// frame, the slide check (slide_check.h) against that noise, and the look-alike check
// (distinctiveness.h).

#include <optional>

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/symmetry.h"
#include "lmk/landmark/capture_findings.h"
#include "lmk/landmark/distinctiveness.h"
#include "lmk/landmark/find_settings.h"
#include "lmk/landmark/landmark.h"
#include "lmk/landmark/slide_check.h"

namespace lmk {

struct CaptureCheck {
  CaptureFindings findings;
  SlideReport slides;  ///< every free direction, symmetries included, for the capture's advice
  /// The look-alike check's search; nothing when it was not run (no scene, a flat landmark, or
  /// not asked for).
  std::optional<DistinctivenessReport> look_alikes;
};

/// Checks `landmark` as captured from `capture_scene` (its first view's cloud, in the capture
/// frame), the look-alike check searching with `settings` (FindSettings::scene.up set to the
/// landmark's; progress and threads as the caller wants them) when `look_alikes` is true. Without a
/// scene (null: a file from before format 4) the noise is the sensor model's (`settings.scene`'s
/// DepthNoise) and there is no look-alike check. A flat landmark (CaptureSettings::allow_flat) is
/// meant to slide on its plane: it has no slides and no look-alike check.
CaptureCheck check_capture(const Landmark& landmark, const PointCloud* capture_scene,
                           const FindSettings& settings = {}, bool look_alikes = true);

/// The symmetry the capture found (CaptureFindings::symmetry_axes), in the landmark's box frame
/// with its axis through the point the capture found it through: an axis of revolution. Nothing
/// when it found none. A landmark symmetric about several axes (a ball) gets its first only: the
/// evaluation that uses it (lmk eval, issue #59) then forgives fewer turns than it could, never
/// more.
std::optional<Symmetry> capture_symmetry(const Landmark& landmark);

}  // namespace lmk
