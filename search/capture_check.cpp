// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/capture_check.h"

namespace lmk {

CaptureCheck check_capture(const Landmark& landmark, const PointCloud* scene,
                           const FindSettings& settings, bool look_alikes) {
  CaptureCheck check;
  static_cast<ShapeCheck&>(check) = check_shape(landmark, scene, settings.scene);
  if (landmark.settings.allow_flat || !scene || !look_alikes) return check;
  CaptureFindings& f = check.findings;
  check.look_alikes = check_distinctiveness(*scene, landmark, settings);
  const DistinctivenessReport& r = *check.look_alikes;
  f.look_alike_checked = true;
  f.found_itself = r.found_itself;
  f.look_alikes = r.other_instances.size();
  if (!r.other_instances.empty() && r.found_itself && r.own_error > 0.0)
    f.look_alike_ratio = r.other_instances.front().error / r.own_error;
  else if (!r.other_instances.empty())
    f.look_alike_ratio = 1.0;  // nothing better to compare with: as good as the landmark
  return check;
}

}  // namespace lmk
