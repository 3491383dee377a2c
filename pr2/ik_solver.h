// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Inverse kinematics for a serial chain by damped least squares (Levenberg-Marquardt on the
// geometric Jacobian), with joint limits, continuous joints and seeded restarts.
//
// Why not KDL or Ceres: the PR2 arm is a 7-joint chain whose FK and Jacobian cost about a
// microsecond, so a small dedicated solver meets the 2 ms budget, needs no dependency beyond
// the dependencies of docs/developing.md, and can say precisely why a target failed (workspace or
// joint limits).

#include <cstdint>

#include "lmk/pr2/robot_model.h"

namespace lmk {

struct IkSettings {
  double position_tolerance = 1e-4;  ///< m; the issue's bound is 1 mm
  double rotation_tolerance = 1e-3;  ///< rad; the issue's bound is 0.5 deg = 8.7e-3 rad
  int max_iterations = 150;          ///< per attempt
  int max_attempts = 30;             ///< the given seed, then seeded random restarts
  int solutions_to_compare = 3;      ///< successful attempts among which the nearest wins
  double damping = 0.05;             ///< lambda of the damped pseudo-inverse
  double rotation_weight = 0.3;      ///< metres per radian when weighing rotation errors
  std::uint64_t random_seed = 1;     ///< restarts are deterministic
};

/// Solves T_root_tip = target for `chain`. The seed (empty: mid-range) is tried first; among the
/// successful attempts the solution nearest the seed is returned. No returned joint value leaves
/// its limits; continuous joints are wrapped to [-pi, pi].
IkResult solve_ik(const KinematicChain& chain, const Eigen::Isometry3d& T_root_target,
                  const std::vector<double>& seed, const IkSettings& settings = {});

}  // namespace lmk
