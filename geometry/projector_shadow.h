// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Free space seen through a structured-light sensor's shadow.
//
// A Kinect v1 returns no depth where its projector, `baseline` metres along the camera's +x,
// cannot light the surface: in the image, a strip left of each nearer object, on whatever lies
// behind it. The camera still looks through that strip: its ray passes beside the nearer object
// and ends on a surface the projector cannot see. The ray is lit, hence empty, until it enters the
// shadow volume behind the object's edge, so the space along it up to there was observed free,
// even though the pixel holds no point: from the object's depth next to the edge to the far
// side's depth across the strip. Without this, every landmark loses the free space on its left,
// which is what tells a corner from the middle of an edge (the chair's backrest corner: 20% of
// its empty space).
//
// A strip of no returns counts as a shadow only when its two ends say so: a farther surface on its
// left, a nearer one on its right, and the strip as wide as the projector's offset makes it,
// baseline (1/z_near - 1/z_far) in normalised image coordinates. A black object that returns
// nothing is rarely exactly that wide, and its space is not carved.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct ProjectorShadowSettings {
  double baseline = 0.075;        ///< projector offset along the camera's +x, m (Kinect v1)
  double width_tolerance = 2.0;   ///< pixels by which a strip may differ from the expected width
  double min_depth_ratio = 1.03;  ///< the far side lies at least this factor deeper
};

/// A no-return pixel in a projector shadow.
struct ShadowRay {
  std::size_t pixel = 0;  ///< its index in the cloud
  /// Where its camera ray enters the shadow volume (at most at the far side's depth), in the
  /// cloud's frame: the ray is observed free up to there.
  Eigen::Vector3f end = Eigen::Vector3f::Zero();
};

/// Every no-return pixel of an organised cloud that lies in a projector shadow, row by row.
/// Empty for an unorganised cloud.
std::vector<ShadowRay> projector_shadow_rays(const PointCloud& organised,
                                             const ProjectorShadowSettings& settings = {});

/// The rays' ends alone (ShadowRay::end).
std::vector<Eigen::Vector3f> projector_shadow_ray_ends(
    const PointCloud& organised, const ProjectorShadowSettings& settings = {});

}  // namespace lmk
