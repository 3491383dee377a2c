// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/distinctiveness.h"

namespace lmk {

DistinctivenessReport check_distinctiveness(const PointCloud& capture_scene,
                                            const Landmark& landmark,
                                            const FindSettings& settings) {
  DistinctivenessReport report;
  FindSettings as_captured = settings;
  as_captured.scene.veil_angle = landmark.settings.veil_angle;
  as_captured.scene.depth_smoothing = landmark.settings.depth_smoothing;
  report.search = find_landmark(capture_scene, landmark, as_captured);
  // The captured instance sits at the identity: the capture frame is the capture scene's frame.
  const Eigen::Vector3d captured = landmark.box.center();
  for (const Match& m : report.search.matches) {
    if ((m.box.center() - captured).norm() <= settings.selection.nms_radius) {
      if (!report.found_itself || m.error < report.own_error) report.own_error = m.error;
      report.found_itself = true;
    } else {
      report.other_instances.push_back(m);
    }
  }
  return report;
}

}  // namespace lmk
