// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Rotational symmetry of a landmark, in its box frame. A symmetric landmark's pose is fixed only up
// to its symmetry: a bowl's rim found at any turn about its axis is the same rim. Evaluation
// forgives those turns when it compares poses, and execution picks the turn nearest the one the
// demonstration saw.

#include <Eigen/Geometry>
#include <optional>

namespace lmk {

/// None, or an axis (in the landmark's box frame) about which rotations leave the landmark
/// unchanged: any rotation for an axis of revolution (a bowl's or a ball's vertical axis), or
/// multiples of 360/order degrees for an n-fold symmetry (a bar handle turned half a turn about
/// the normal of the face it is mounted on).
struct Symmetry {
  std::optional<Eigen::Vector3d> axis;
  int order = 0;  ///< 0: an axis of revolution; n >= 2: n-fold
  /// A point the axis passes through, box frame: the box centre unless a capture found the axis
  /// elsewhere (capture_findings.h). Turning about an axis off the centre moves the box centre, so
  /// the evaluation compares positions at this point (evaluation_protocol.h, translation_error).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

/// Among the rotations R * turn that the symmetry makes equivalent to R (turns about the axis, in
/// R's own frame), the one nearest R_reference. Without an axis, R itself. For an axis of
/// revolution the turn is the twist of R^T R_reference about the axis (swing-twist
/// decomposition), which leaves only the swing between the two.
Eigen::Matrix3d nearest_symmetric_rotation(const Eigen::Matrix3d& R,
                                           const Eigen::Matrix3d& R_reference,
                                           const Symmetry& symmetry);

}  // namespace lmk
