// SPDX-License-Identifier: BSD-3-Clause
// Uses lmk through its installed headers: builds a cloud, crops it with a box, downsamples it, and
// lists the search's error metrics from a header of a module's subfolder (search/metrics/).
#include <lmk/geometry/box.h>
#include <lmk/geometry/filters.h>
#include <lmk/geometry/version.h>
#include <lmk/geometry/voxel_grid.h>
#include <lmk/search/find_landmark.h>
#include <lmk/search/metrics/error_metrics.h>

#include <cstdio>

int main() {
  lmk::PointCloud cloud;
  for (int i = 0; i < 10; ++i) cloud.points.emplace_back(0.1f * i, 0.0f, 0.0f);
  cloud.set_unorganized();
  const lmk::Box box(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.5, 0.5, 0.5));
  const lmk::PointCloud inside = lmk::crop(cloud, box);
  const lmk::PointCloud coarse = lmk::voxel_downsample(cloud, 0.25);
  const std::size_t metrics = lmk::error_metric_names().size();
  std::printf("lmk %s: %zu points in the box, %zu voxels, %zu error metrics\n", lmk::kVersion,
              inside.size(), coarse.size(), metrics);
  return inside.size() == 3 && coarse.size() == 4 && metrics > 0 ? 0 : 1;
}
