// SPDX-License-Identifier: BSD-3-Clause
// Uses lmk through its installed headers: builds a cloud, crops it with a box, downsamples it.
#include <lmk/geometry/box.h>
#include <lmk/geometry/filters.h>
#include <lmk/geometry/version.h>
#include <lmk/geometry/voxel_grid.h>

#include <cstdio>

int main() {
  lmk::PointCloud cloud;
  for (int i = 0; i < 10; ++i) cloud.points.emplace_back(0.1f * i, 0.0f, 0.0f);
  cloud.set_unorganized();
  const lmk::Box box(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.5, 0.5, 0.5));
  const lmk::PointCloud inside = lmk::crop(cloud, box);
  const lmk::PointCloud coarse = lmk::voxel_downsample(cloud, 0.25);
  std::printf("lmk %s: %zu points in the box, %zu voxels\n", lmk::kVersion, inside.size(),
              coarse.size());
  return inside.size() == 3 && coarse.size() == 4 ? 0 : 1;
}
