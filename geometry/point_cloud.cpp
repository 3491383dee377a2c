// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/point_cloud.h"

#include <algorithm>
#include <string>

#include "lmk/geometry/error.h"

namespace lmk {

PointCloud::PointCloud(std::vector<Eigen::Vector3f> pts) : points(std::move(pts)) {
  width = static_cast<std::uint32_t>(points.size());
}

std::size_t PointCloud::count_finite() const {
  return static_cast<std::size_t>(
      std::count_if(points.begin(), points.end(), [](const auto& p) { return is_finite(p); }));
}

Eigen::AlignedBox3f PointCloud::bounds() const {
  Eigen::AlignedBox3f box;  // default-constructed empty
  for (const auto& p : points) {
    if (is_finite(p)) box.extend(p);
  }
  return box;
}

void PointCloud::set_unorganized() {
  width = static_cast<std::uint32_t>(points.size());
  height = 1;
}

PointCloud PointCloud::select(const Indices& indices) const {
  PointCloud out;
  out.T_cloud_sensor = T_cloud_sensor;
  out.points.reserve(indices.size());
  for (Index i : indices) out.points.push_back(points[i]);
  if (has_normals()) {
    out.normals.reserve(indices.size());
    for (Index i : indices) out.normals.push_back(normals[i]);
  }
  if (has_colors()) {
    out.colors.reserve(indices.size());
    for (Index i : indices) out.colors.push_back(colors[i]);
  }
  if (has_labels()) {
    out.labels.reserve(indices.size());
    for (Index i : indices) out.labels.push_back(labels[i]);
  }
  out.set_unorganized();
  return out;
}

PointCloud PointCloud::transformed(const Eigen::Isometry3d& T_new_old) const {
  PointCloud out = *this;
  const Eigen::Isometry3f T = T_new_old.cast<float>();
  for (auto& p : out.points) {
    if (is_finite(p)) p = T * p;
  }
  for (auto& n : out.normals) n = T.linear() * n;
  out.T_cloud_sensor = T_new_old * T_cloud_sensor;
  return out;
}

void PointCloud::validate(const std::string& what) const {
  const auto check = [&](std::size_t n, const char* name) {
    if (n != 0 && n != points.size()) {
      throw Error(what + ": " + std::to_string(n) + " " + name + " for " +
                  std::to_string(points.size()) + " points");
    }
  };
  check(normals.size(), "normals");
  check(colors.size(), "colours");
  check(labels.size(), "labels");
  if (static_cast<std::size_t>(width) * height != points.size()) {
    throw Error(what + ": width x height = " + std::to_string(width) + " x " +
                std::to_string(height) + " does not match " + std::to_string(points.size()) +
                " points");
  }
}

}  // namespace lmk
