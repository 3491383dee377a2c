// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Landmarks defined on the real data in ../shared/data, shared by tests and benchmarks so that
// every measurement uses the same definition.

#include <filesystem>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"

namespace lmk {

/// The milk-carton landmark box in pcl/milk_cartoon_all_small_clorox.pcd, from the carton's own
/// crop (pcl/milk.pcd, whose true pose in the scene is the identity): the crop's axis-aligned
/// bounds in the camera frame, plus 2 cm on the sides that face free space (left, right, top and
/// front; the camera's y points down and z away), none on the table side or the occluded back.
Box milk_carton_box(const PointCloud& carton_crop);

/// The real milk-carton workload: the 640x480 Kinect frame pcl/milk_cartoon_all_small_clorox.pcd
/// and the landmark captured in it with milk_carton_box (default capture settings).
struct MilkWorkload {
  PointCloud scene;
  Box box;  ///< the capture box, scene frame
  Landmark landmark;
};
/// Loads it from `data_dir` (the ../shared/data layout). Throws lmk::Error when a file is missing.
MilkWorkload load_milk_workload(const std::filesystem::path& data_dir);

}  // namespace lmk
