// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Landmark boxes as a user would draw them on a real frame, chosen by a rule fixed before any
// search is measured (docs/datasets.md, "Real RGB-D sequences"): a box goes where the frame has
// structure (an object on a surface, a handle, a corner or an edge of furniture), never on bare
// wall, floor or table top, which a user would not pick and the capture would refuse as flat.
//
// The rule, in full:
// 1. The frame is reduced to voxels of a 30th of the box's side, with normals
// (geometry/voxel_normals.h), keeping the
//    points between min_depth and max_depth.
// 2. The points are binned in cubic cells of half the box's side, anchored at the camera. A cell
//    with at least min_cell_points points is structured when at least min_off_plane of its normals
//    lie more than off_plane_angle from its dominant direction (the normal most others agree
//    with), and its points stand off their best plane by more than the depth noise at its depth
//    (RMS against one measurement sigma): a far, bare surface's normals scatter with the noise.
// 3. A box is axis-aligned in the camera frame, of side box_side, centred on the centroid of a
//    structured cell's points, and must project wholly into the image (a user draws around what
//    the frame shows).
// 4. Boxes are taken most structured first: by the fraction of normals off both the dominant and
//    the second direction (an object or a corner before a plain edge of two planes), then off the
//    dominant one. A box whose centre is within one side of a box already taken is skipped; at
//    most max_boxes per frame.

#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/depth_image.h"
#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct UserBoxRule {
  double box_side = 0.3;  ///< m
  /// Voxels per box side: the frame's resolution follows the box's, so that a cell (half a box)
  /// holds up to 15 x 15 voxels of a surface facing the camera at any box size.
  double voxels_per_side = 30.0;
  double min_depth = 0.2, max_depth = 3.5;  ///< m
  std::size_t min_cell_points = 40;
  double off_plane_angle = 0.5236;  ///< rad (30 degrees)
  double min_off_plane = 0.2;       ///< fraction of a cell's normals
  std::size_t max_boxes = 6;
  DepthNoise noise;  ///< the sensor's (a Kinect v1's by default)
};

/// The boxes the rule draws on `frame` (organised, camera optical frame), in the frame's frame,
/// most structured first.
std::vector<Box> user_like_boxes(const PointCloud& frame, const PinholeIntrinsics& intrinsics,
                                 const UserBoxRule& rule = {});

}  // namespace lmk
