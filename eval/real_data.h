#pragma once
// Landmarks defined on the real data in ../shared/data, shared by tests and benchmarks so that
// every measurement uses the same definition.

#include "geometry/box.h"
#include "geometry/point_cloud.h"

namespace lmk {

/// The milk-carton landmark box in pcl/milk_cartoon_all_small_clorox.pcd, from the carton's own
/// crop (pcl/milk.pcd, whose true pose in the scene is the identity): the crop's axis-aligned
/// bounds in the camera frame, plus 2 cm on the sides that face free space (left, right, top and
/// front; the camera's y points down and z away), none on the table side or the occluded back.
Box milk_carton_box(const PointCloud& carton_crop);

}  // namespace lmk
