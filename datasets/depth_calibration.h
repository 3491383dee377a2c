// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A depth camera's depth error, fitted from a sequence of its frames with known poses (issue #33).
//
// A real Kinect v1 reads depth a little too far, more so the farther and the nearer the image's
// edge: on the kitchen sequence of ../shared/data/real the frames, moved into each other by their
// poses, disagreed by up to 4 mm/m^2 across the image, and a landmark cut from one frame fitted
// another 3 degrees askew (docs/evaluation.md, "A lead: calibrating the Kinect's depth"). The
// model: z' = z + D z^2, D constant over each cell of a grid over the image. The fit: every
// pair of frames a few frames apart, each sampled pixel of one moved by the poses into the other,
// gives one equation D(b) z_b^2 - D(a) z_a^2 = z_a->b - z_b (the corrected depths agree); damped
// least squares over the cells (Eigen). The frames the fit uses should not be those an evaluation
// then measures on.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "lmk/geometry/depth_correction.h"
#include "lmk/geometry/pinhole_intrinsics.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct DepthCalibrationSettings {
  int cols = 8, rows = 6;
  std::size_t min_gap = 5, max_gap = 20;  ///< pairs of frames this many apart in the list
  int pixel_step = 6;                     ///< every this-many-th pixel, across and down
  double max_difference = 0.05;  ///< m: farther apart is another surface (occlusion), not error
  /// Damping of each cell's D towards 0, relative to the largest cell's weight: it keeps cells
  /// that few pixels see from wandering.
  double damping = 1e-3;
};

/// Fits the correction to `frames` (organised clouds in their camera's optical frame, raw) seen
/// from `T_world_camera` through `intrinsics`. lmk::Error when the frames give too few
/// correspondences (fewer than 100 per cell).
DepthCalibration fit_depth_correction(const std::vector<const PointCloud*>& frames,
                                      const std::vector<Eigen::Isometry3d>& T_world_camera,
                                      const PinholeIntrinsics& intrinsics,
                                      const DepthCalibrationSettings& settings = {});

}  // namespace lmk
