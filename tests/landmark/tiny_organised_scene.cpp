// SPDX-License-Identifier: BSD-3-Clause
#include "tiny_organised_scene.h"

#include <gtest/gtest.h>

#include "lmk/search/scene_index.h"

namespace lmk {
namespace {
constexpr double kF = 40.0, kCx = 19.5, kCy = 14.5;
}  // namespace

Eigen::Vector3f on_tiny_ray(int u, int v, double depth) {
  return Eigen::Vector3f(static_cast<float>((u - kCx) / kF * depth),
                         static_cast<float>((v - kCy) / kF * depth), static_cast<float>(depth));
}

PointCloud tiny_wall(const std::function<double(int, int)>& depth_at, int columns) {
  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(columns);
  cloud.height = kTinyHeight;
  for (int v = 0; v < kTinyHeight; ++v)
    for (int u = 0; u < columns; ++u) cloud.points.push_back(on_tiny_ray(u, v, depth_at(u, v)));
  return cloud;
}

bool in_tiny_landmark(int u, int v) { return u >= 18 && u <= 20 && v >= 13 && v <= 15; }

Landmark tiny_landmark() {
  Landmark landmark;
  landmark.name = "patch";
  for (int v = 13; v <= 15; ++v)
    for (int u = 18; u <= 20; ++u) landmark.points.points.push_back(on_tiny_ray(u, v, 1.0));
  landmark.points.set_unorganized();
  landmark.box = Box(Eigen::Isometry3d(Eigen::Translation3d(0, 0, 1.0)), {0.2, 0.2, 0.1});
  landmark.sensor_origin = Eigen::Vector3d::Zero();  // captured from where the scene is seen
  // The capture saw the wall with rays 2 mm apart, denser than the 5 mm voxels, so that every
  // voxel in front of it was observed (this image's own pixels lie 2.5 cm apart at 1 m).
  std::vector<Eigen::Vector3f> capture_scene;
  for (int i = -60; i <= 60; ++i)
    for (int k = -60; k <= 60; ++k) capture_scene.emplace_back(0.002f * i, 0.002f * k, 1.0f);
  prepare_landmark(landmark, &capture_scene);
  return landmark;
}

ErrorTerms evaluate_tiny(const std::string& metric, const Landmark& landmark,
                         const PointCloud& scene, const SceneSettings& settings) {
  const SceneIndex index(scene, settings);
  EXPECT_NE(index.range_image(), nullptr);
  const KdTree tree(landmark.points);
  return find_error_metric(metric).evaluate(
      SceneView{index}, LandmarkView{landmark.points, tree, landmark.box, landmark},
      Eigen::Isometry3d::Identity());
}

}  // namespace lmk
