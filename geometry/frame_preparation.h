// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a capture and a search do to an organised frame before anything else reads it, the same on
// both sides so that a landmark and the scenes it is searched in are alike: the veil points go
// (geometry/veil_points.h), then the depth is smoothed (geometry/depth_smoothing.h).

#include <optional>

#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// `frame` prepared: veil points within `veil_angle` (rad, 0: none) dropped, then the depth
/// smoothed over a window of `smoothing_radius` pixels (0: none). Nothing when neither applies
/// (an unorganised frame, or both off): the caller reads `frame` itself, uncopied.
std::optional<PointCloud> prepared_frame(const PointCloud& frame, double veil_angle,
                                         int smoothing_radius, const DepthNoise& noise);

}  // namespace lmk
