// SPDX-License-Identifier: BSD-3-Clause
// Built by catkin against an installed lmk: crops a cloud with a box (lmk::geometry) and names the
// PR2 arm groups (lmk::pbd), the two layers a PbD stack builds on.
#include <lmk/geometry/box.h>
#include <lmk/geometry/filters.h>
#include <lmk/geometry/version.h>
#include <lmk/pbd/program.h>

#include <cstdio>

int main() {
  lmk::PointCloud cloud;
  for (int i = 0; i < 10; ++i) cloud.points.emplace_back(0.1f * i, 0.0f, 0.0f);
  cloud.set_unorganized();
  const lmk::Box box(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.5, 0.5, 0.5));
  const std::size_t inside = lmk::crop(cloud, box).size();
  const std::string group = lmk::arm_group(lmk::Arm::kRight);
  std::printf("lmk %s in a catkin package: %zu of %zu points in the box; arm group %s\n",
              lmk::kVersion, inside, cloud.size(), group.c_str());
  return inside == 3 && group == "right_arm" ? 0 : 1;
}
