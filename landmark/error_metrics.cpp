#include "landmark/error_metrics.h"

#include <cmath>
#include <limits>

#include "geometry/error.h"

namespace lmk {
namespace {

// Algorithm 2, lines 5-10: each scene point in the candidate box adds its distance to the nearest
// landmark point, and marks that point visited. Scene points are mapped into the capture frame.
void add_scene_to_landmark(const SceneView& scene, const LandmarkView& landmark,
                           const Eigen::Isometry3d& T_capture_scene, const Indices& in_box,
                           std::vector<char>& visited, ErrorTerms& terms) {
  const Eigen::Isometry3f T = T_capture_scene.cast<float>();
  for (Index i : in_box) {
    const auto nearest = landmark.tree.nearest(T * scene.points.points[i]);
    if (!nearest) continue;
    terms.scene_to_landmark_sum += std::sqrt(nearest->squared_distance);
    ++terms.scene_to_landmark_count;
    visited[nearest->index] = 1;
  }
}

// Algorithm 2 exactly: unvisited landmark points add their distance to the nearest scene point,
// searched over the whole scene.
ErrorTerms paper_metric(const SceneView& scene, const LandmarkView& landmark,
                        const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const Indices in_box = scene_points_in_box(scene, landmark.box.transformed(T_scene_capture));
  terms.scene_points_in_box = in_box.size();
  std::vector<char> visited(landmark.points.size(), 0);
  add_scene_to_landmark(scene, landmark, T_scene_capture.inverse(), in_box, visited, terms);
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (visited[j]) continue;
    const auto nearest = scene.tree.nearest(T * landmark.points.points[j]);
    if (!nearest) continue;
    terms.landmark_to_scene_sum += std::sqrt(nearest->squared_distance);
    ++terms.landmark_to_scene_count;
  }
  terms.finish();
  return terms;
}

// The authors' code (rapid_perception): the landmark->scene term searches only the scene points
// inside the box, and counts a distance only when it is under 5 cm.
constexpr double kRapidCap = 0.05;

ErrorTerms rapid_metric(const SceneView& scene, const LandmarkView& landmark,
                        const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const Indices in_box = scene_points_in_box(scene, landmark.box.transformed(T_scene_capture));
  terms.scene_points_in_box = in_box.size();
  std::vector<char> visited(landmark.points.size(), 0);
  add_scene_to_landmark(scene, landmark, T_scene_capture.inverse(), in_box, visited, terms);
  const KdTree box_tree(scene.points.select(in_box));
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (visited[j]) continue;
    const auto nearest = box_tree.nearest(T * landmark.points.points[j]);
    if (!nearest) continue;
    const double d = std::sqrt(nearest->squared_distance);
    if (d >= kRapidCap) continue;
    terms.landmark_to_scene_sum += d;
    ++terms.landmark_to_scene_count;
  }
  terms.finish();
  return terms;
}

}  // namespace

void ErrorTerms::finish() {
  const std::size_t count = scene_to_landmark_count + landmark_to_scene_count;
  error = count == 0 ? std::numeric_limits<double>::infinity()
                     : (scene_to_landmark_sum + landmark_to_scene_sum) / static_cast<double>(count);
}

Indices scene_points_in_box(const SceneView& scene, const Box& box) {
  // Every point of the box lies within its half-diagonal of the centre.
  const float radius = static_cast<float>(0.5 * box.size.norm()) * (1.0f + 1e-6f);
  Indices out;
  for (const Neighbor& n : scene.tree.radius(box.center().cast<float>(), radius)) {
    if (box.contains(scene.points.points[n.index])) out.push_back(n.index);
  }
  std::sort(out.begin(), out.end());
  return out;
}

const std::vector<ErrorMetric>& error_metrics() {
  static const std::vector<ErrorMetric> metrics = {
      {"paper",
       "Algorithm 2 of Huang & Cakmak: mean of scene->landmark distances over the scene points in "
       "the box and landmark->scene distances (whole scene) over the unvisited landmark points",
       paper_metric},
      {"rapid",
       "the authors' code: as 'paper', but the landmark->scene term searches only the scene points "
       "in the box and counts only distances under 5 cm",
       rapid_metric},
  };
  return metrics;
}

const ErrorMetric& find_error_metric(const std::string& name) {
  std::string known;
  for (const ErrorMetric& m : error_metrics()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw Error("unknown error metric '" + name + "' (known: " + known + ")");
}

}  // namespace lmk
