// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The capture check's first half (issue #59), which needs no search: the noise of the capture
// frame at the box and the slide check (slide_check.h) against it, recorded as the landmark's
// CaptureFindings. The look-alike half searches the capture scene and lies above the search
// (search/capture_check.h); a file written before format 4 gains this half on load.

#include <optional>

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/symmetry.h"
#include "lmk/landmark/capture_findings.h"
#include "lmk/landmark/landmark.h"
#include "lmk/landmark/scene_settings.h"
#include "lmk/landmark/slide_check.h"

namespace lmk {

struct ShapeCheck {
  CaptureFindings findings;  ///< present, with the noise, the slide and the symmetry axes
  SlideReport slides;  ///< every free direction, symmetries included, for the capture's advice
};

/// Checks the shape of `landmark` as captured from `capture_scene` (its first view's cloud, in the
/// capture frame): the frame's noise at the box, and the slide check against it. Without a scene
/// (null: a file from before format 4) the noise is the sensor model's (`scene`'s DepthNoise). A
/// flat landmark (CaptureSettings::allow_flat) is meant to slide on its plane: it has no slides.
ShapeCheck check_shape(const Landmark& landmark, const PointCloud* capture_scene,
                       const SceneSettings& scene = {});

/// The symmetry the capture found (CaptureFindings::symmetry_axes), in the landmark's box frame
/// with its axis through the point the capture found it through: an axis of revolution. Nothing
/// when it found none. A landmark symmetric about several axes (a ball) gets its first only: the
/// evaluation that uses it (lmk eval, issue #59) then forgives fewer turns than it could, never
/// more.
std::optional<Symmetry> capture_symmetry(const Landmark& landmark);

}  // namespace lmk
