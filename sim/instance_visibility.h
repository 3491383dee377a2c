// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How much of a landmark instance a sensor sees: the ground truth that the range, viewpoint and
// occlusion benchmarks record with each instance (issue #16), so that their tables can be split
// by it and an instance nobody could see is not held against a method.

#include <Eigen/Geometry>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk {

/// `landmark`'s captured points moved from their capture box onto `instance` (a box pose of the
/// landmark in the world), world frame, in the landmark's point order.
std::vector<Eigen::Vector3d> points_on_instance(const Landmark& landmark, const Box& instance);

/// For each point of points_on_instance, whether a sensor sees it: it projects into the image and
/// the exact frame `exact` (rendered without noise by `sensor`, with its pose) holds a surface
/// within `tolerance` of its depth at that pixel.
std::vector<char> seen_on_instance(const Landmark& landmark, const Box& instance,
                                   const PointCloud& exact, const DepthSensorSettings& sensor,
                                   double tolerance = 0.015);

/// The fraction of `landmark`'s captured points that a sensor does not see on the instance
/// `instance` (a box pose of the landmark in the world): each point, moved from its capture box
/// onto the instance, is seen when it projects into the image and the exact frame `exact` (rendered
/// without noise by `sensor`, with its pose) holds a surface within `tolerance` of its depth at
/// that pixel. Points behind another surface, turned away, out of range or in the projector's
/// shadow are hidden. 0 for a landmark without points.
double hidden_fraction(const Landmark& landmark, const Box& instance, const PointCloud& exact,
                       const DepthSensorSettings& sensor, double tolerance = 0.015);

/// Where a sensor may look at a landmark from.
struct ViewpointRange {
  double min_range = 0.7, max_range = 3.5;  ///< distance from the sensor to the target, m
  double max_azimuth = M_PI / 3.0;  ///< about the vertical, from the reference direction, rad
  double min_height = 0.8, max_height = 1.8;  ///< the sensor's height above z = 0, m
};

/// A sensor pose (optical frame, z forward, y down) looking at `target` from a random place of
/// `range`: its distance and height uniform in their ranges, its direction within max_azimuth of
/// the horizontal direction from the target to `reference` (where the landmark was demonstrated
/// from). When the height cannot be reached at that distance, the sensor stays within 70 degrees
/// of the horizontal. Deterministic in `seed`.
Eigen::Isometry3d random_viewpoint(const Eigen::Vector3d& target, const Eigen::Vector3d& reference,
                                   std::uint64_t seed, const ViewpointRange& range = {});

}  // namespace lmk
