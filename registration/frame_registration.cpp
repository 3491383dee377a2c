// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/frame_registration.h"

#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/voxel_normals.h"

namespace lmk {

PointCloud reduce_for_registration(const PointCloud& frame,
                                   const FrameRegistrationSettings& settings) {
  return downsample_with_normals(frame, settings.leaf, frame.sensor_origin());
}

IcpResult register_frames(const PointCloud& source, const PointCloud& target,
                          const Eigen::Isometry3d& T_target_source,
                          const FrameRegistrationSettings& settings) {
  const KdTree tree(target);
  const KdTreeTarget icp_target(target, tree);
  IcpSettings icp_settings;
  icp_settings.correspondences = settings.correspondences;
  icp_settings.termination = settings.termination;
  return icp(source.points, icp_target, T_target_source, icp_settings);
}

}  // namespace lmk
