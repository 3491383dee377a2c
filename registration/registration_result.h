// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a rigid registration returns: the pose, iterations and convergence every one has, and what
// only its kind fills: ICP's correspondences (icp.h), the Ceres refinement's cost (refine_pose.h).

#include <Eigen/Geometry>
#include <cstddef>
#include <limits>

namespace lmk {

/// What every registration returns.
struct RegistrationResult {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  int iterations = 0;
  /// ICP: the last step moved the source by less than the tolerances; refinement: Ceres reports
  /// convergence.
  bool converged = false;
};

/// ICP's (icp.h, frame_registration.h): the correspondences of its last pass.
struct IcpResult : RegistrationResult {
  /// Correspondences of the last pass (at the returned pose, or with measure_final off, at the
  /// pose before the last step), and their mean absolute residual, m (+inf with none).
  std::size_t inliers = 0;
  double final_error = std::numeric_limits<double>::infinity();
};

/// The Ceres refinement's (refine_pose.h): its robust cost.
struct RefineResult : RegistrationResult {
  /// The robust cost at the start and at the returned pose (never above the start's).
  double initial_cost = 0.0;
  double final_cost = 0.0;
};

}  // namespace lmk
