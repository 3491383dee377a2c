// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/confidence/view_determinacy.h"

#include "lmk/landmark/slide_check.h"
#include "lmk/search/metrics/grid_metrics.h"

namespace lmk::detail {

bool shows_too_little_to_fix(const SceneIndex& scene, const Landmark& landmark,
                             const Eigen::Isometry3d& T_scene_capture) {
  if (!landmark.multi_view()) return false;
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  const Eigen::Vector3f sensor = scene.T_scene_sensor().translation().cast<float>();
  const Eigen::Vector3d centre = T_scene_capture * landmark.box.center();
  const std::vector<char> facing = facing_sensor(landmark.points, T, sensor, centre.cast<float>(),
                                                 2.0 * landmark.settings.leaf_size);
  Indices shown;
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (facing[j] &&
        !unseen_by_sensor(scene, T * landmark.points.points[j], UnseenPoints::outside_image)) {
      shown.push_back(static_cast<Index>(j));
    }
  }
  // Both judged against the noise where the match stands.
  const double range = (centre - scene.T_scene_sensor().translation()).norm();
  const double noise = scene.settings().depth_noise().residual_sigma(range, range);
  // Only a direction left essentially free counts: 10 cm of slide or 60 degrees of turn within the
  // noise, as a cylinder turns and a plane slides. At the protocol's tolerance (25.4 mm, 15
  // degrees) a true L-shape seen from a third camera was turned down too.
  const auto free_directions = [&](const PointCloud& points) {
    std::size_t n = 0;
    for (const Slide& s : slide_check(points, noise).slides) {
      if (s.extent > (s.turn ? 1.047 : 0.1)) ++n;
    }
    return n;
  };
  // Against what the demonstration view itself showed: the landmark a one-view capture makes,
  // which is searched with every point.
  Indices demonstrated;
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (landmark.point_views[j] & 1u) demonstrated.push_back(static_cast<Index>(j));
  }
  return free_directions(landmark.points.select(shown)) >
         free_directions(landmark.points.select(demonstrated));
}

}  // namespace lmk::detail
