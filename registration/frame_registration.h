// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Whole-frame registration: one depth frame aligned onto another of the same place, started from
// a guess of their relative pose. It checks the poses of an RGB-D sequence's pairs (the dataset
// importer) and joins the views of a landmark demonstrated from several (capture_views.h), where
// no pose was given or to refine one.

#include "lmk/geometry/point_cloud.h"
#include "lmk/registration/icp.h"

namespace lmk {

struct FrameRegistrationSettings {
  double leaf = 0.02;  ///< voxels of the reduced frames, m
  /// Within 5 cm, a Huber loss at 1 cm.
  Correspondences correspondences{0.05, {RobustKernel::huber, 0.01}};
  Termination termination{40};
};

/// A frame reduced for registration: its voxel centroids at settings.leaf with normals facing its
/// sensor. Reduce a frame once when it is registered more than once.
PointCloud reduce_for_registration(const PointCloud& frame,
                                   const FrameRegistrationSettings& settings = {});

/// Point-to-plane ICP of `source`'s reduced points against `target`'s (both from
/// reduce_for_registration()), from T_target_source, with settings.correspondences and
/// settings.termination. IcpResult::inliers over source.size() is the share of the source
/// the target explains (the overlap); final_error the mean residual of those.
IcpResult register_frames(const PointCloud& source, const PointCloud& target,
                          const Eigen::Isometry3d& T_target_source,
                          const FrameRegistrationSettings& settings = {});

}  // namespace lmk
