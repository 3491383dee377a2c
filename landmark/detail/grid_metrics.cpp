#include "landmark/detail/grid_metrics.h"

#include <algorithm>
#include <cmath>

#include "landmark/landmark.h"
#include "landmark/scene_index.h"

namespace lmk {

float scene_surface_distance(const SceneIndex& scene, const DistanceField::Sampler& field,
                             const Eigen::Vector3f& q, const Eigen::Vector3f* normal) {
  constexpr float kBackFacing = -0.5f;  // cos(120 degrees)
  const float band = static_cast<float>(scene.field().band());
  const int index = field.closest(q);
  if (index < 0) return band;
  const Eigen::Vector3f delta = q - scene.coarse().points[static_cast<std::size_t>(index)];
  const Eigen::Vector3f& n = scene.coarse().normals[static_cast<std::size_t>(index)];
  if (!n.allFinite()) return std::min(band, delta.norm());
  if (normal != nullptr && normal->allFinite() && normal->dot(n) < kBackFacing) return band;
  const float along = n.dot(delta);
  const float lateral = std::sqrt(std::max(0.0f, delta.squaredNorm() - along * along));
  const float slack = static_cast<float>(0.5 * std::sqrt(3.0) * scene.settings().coarse_leaf);
  const float beside = std::max(0.0f, lateral - slack);
  return std::min(band, std::sqrt(along * along + beside * beside));
}

float landmark_point_distance(const SceneIndex& scene, const DistanceField::Sampler& field,
                              const Eigen::Isometry3f& T_scene_capture, const PointCloud& landmark,
                              std::size_t j) {
  const Eigen::Vector3f q = T_scene_capture * landmark.points[j];
  if (!landmark.has_normals()) return scene_surface_distance(scene, field, q);
  const Eigen::Vector3f normal = T_scene_capture.linear() * landmark.normals[j];
  return scene_surface_distance(scene, field, q, &normal);
}

ErrorTerms vdb_metric(const SceneView& scene, const LandmarkView& landmark,
                      const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const Indices in_box = scene_points_in_box(scene, landmark.box.transformed(T_scene_capture));
  terms.scene_points_in_box = in_box.size();
  const DistanceField::Sampler landmark_field(landmark.landmark.distance);
  std::vector<char> visited(landmark.points.size(), 0);
  const Eigen::Isometry3f T_capture_scene = T_scene_capture.inverse().cast<float>();
  for (Index i : in_box) {
    const Eigen::Vector3f p = T_capture_scene * scene.points().points[i];
    terms.scene_to_landmark_sum += landmark_field.distance(p);
    ++terms.scene_to_landmark_count;
    const int closest = landmark_field.closest(p);
    if (closest >= 0) visited[static_cast<std::size_t>(closest)] = 1;
  }
  const DistanceField::Sampler scene_field(scene.index.field());
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (visited[j]) continue;
    terms.landmark_to_scene_sum +=
        scene_surface_distance(scene.index, scene_field, T * landmark.points.points[j]);
    ++terms.landmark_to_scene_count;
  }
  terms.finish();
  return terms;
}

ErrorTerms visibility_metric(const SceneView& scene, const LandmarkView& landmark,
                             const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  const DistanceField::Sampler scene_field(scene.index.field());
  // Support: a scene surface within two paper leaves (1 cm) of the landmark point.
  const float support = static_cast<float>(2.0 * scene.index.settings().leaf_size);
  std::size_t supported = 0;
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    const float d = landmark_point_distance(scene.index, scene_field, T, landmark.points, j);
    terms.landmark_to_scene_sum += d;
    ++terms.landmark_to_scene_count;
    if (d < support) ++supported;
  }
  terms.coverage = landmark.points.empty() ? 0.0
                                           : static_cast<double>(supported) /
                                                 static_cast<double>(landmark.points.size());

  // Empty space, from the scene's side: its occupied voxels that land in the landmark's
  // observed-empty voxels.
  const DistanceField::Sampler landmark_field(landmark.landmark.distance);
  terms.empty_space_probes = landmark.landmark.empty_space.size();
  for_each_occupied_empty_voxel(scene.index, landmark, T_scene_capture,
                                [&](const Eigen::Vector3f& e, const Eigen::Vector3f&) {
                                  ++terms.empty_space_violations;
                                  terms.scene_to_landmark_sum += landmark_field.distance(e);
                                  ++terms.scene_to_landmark_count;
                                });
  if (terms.empty_space_violations > 0) {
    terms.empty_space_violation_mean =
        terms.scene_to_landmark_sum / static_cast<double>(terms.empty_space_violations);
  }
  terms.finish();
  return terms;
}

}  // namespace lmk
