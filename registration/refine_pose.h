// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Robust pose refinement on SE(3) with Ceres: the final polish of a search candidate.
//
// Each source point contributes the scene distance field at its moved position (the landmark
// surface should lie on the scene surface). Optionally, each empty-space probe (a voxel centre the
// landmark's sensor saw free) contributes max(0, margin - distance): a scene surface must not come
// closer than `margin` to space that was empty. A robust loss discounts outliers such as clutter
// touching the landmark.

#include <Eigen/Geometry>
#include <vector>

#include "lmk/occupancy/distance_field.h"
#include "lmk/registration/registration_result.h"
#include "lmk/registration/robust_loss.h"

namespace lmk {

struct RefineSettings {
  RobustLoss loss{RobustKernel::huber, 0.005};
  int max_iterations = 15;
  double empty_space_weight = 0.0;   ///< weight of each empty-space residual; 0 disables them
  double empty_space_margin = 0.01;  ///< m
};

/// Refines `T_target_source` so that `source` lies on the surface of `target_field`. The
/// result never has a higher cost than the start: if Ceres fails to improve, the start is
/// returned. Thread-safe: runs may share one field. Throws lmk::Error for bad settings.
RefineResult refine_pose(const std::vector<Eigen::Vector3f>& source,
                         const DistanceField& target_field,
                         const Eigen::Isometry3d& T_target_source,
                         const RefineSettings& settings = {},
                         const std::vector<Eigen::Vector3f>& empty_space = {});

}  // namespace lmk
