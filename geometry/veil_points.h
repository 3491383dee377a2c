// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Veil points: the mixed pixels a depth camera returns along a depth discontinuity, between the
// foreground edge and the background behind it. They lie on a surface nearly parallel to the
// sensor's rays that is not there, and differ from view to view: a landmark cut in one frame
// carries a fringe that no other frame shows (its fit there suffers), and a scene's fringe
// stands in space a landmark saw empty (its empty-space test fails). Synthetic frames have none;
// real Kinect and RealSense frames have a fringe at every silhouette (docs/datasets.md, "Real
// RGB-D sequences").
//
// A point is a veil point when the step to one of its four image neighbours runs within
// `max_angle` of the ray through it: a surface seen that edge-on returns no depth on a real
// sensor, so such a step is a discontinuity, not a surface. The foreground's last pixel goes too.

#include <cstddef>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// Sets the veil points of an organised cloud to NaN (the organisation stays), rays from its
/// sensor (T_cloud_sensor). Returns how many. An unorganised cloud, or max_angle <= 0, is left as
/// it is.
std::size_t remove_veil_points(PointCloud& cloud, double max_angle);

}  // namespace lmk
