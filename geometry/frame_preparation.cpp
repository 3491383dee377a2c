// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/frame_preparation.h"

#include "lmk/geometry/depth_smoothing.h"
#include "lmk/geometry/veil_points.h"

namespace lmk {

std::optional<PointCloud> prepared_frame(const PointCloud& frame, double veil_angle,
                                         int smoothing_radius, const DepthNoise& noise) {
  if (!frame.is_organized() || (veil_angle <= 0.0 && smoothing_radius <= 0)) return std::nullopt;
  PointCloud prepared = frame;
  // The veil first: its mixed pixels lie between two surfaces and belong to neither mean.
  if (veil_angle > 0.0) remove_veil_points(prepared, veil_angle);
  smooth_depth(prepared, smoothing_radius, noise);
  return prepared;
}

}  // namespace lmk
