// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Box: an oriented box given by the pose of its centre and its full side lengths.
//
// This is the landmark box B of Huang & Cakmak: the user draws it around the landmark, the points
// inside give its shape, and its empty margins say where space must stay free.

#include <Eigen/Geometry>
#include <array>

namespace lmk {

struct Box {
  /// T_frame_box: pose of the box centre in the frame the box is expressed in.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Full side lengths along the box's own x, y and z axes, in metres.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();

  Box() = default;
  Box(const Eigen::Isometry3d& pose_in, const Eigen::Vector3d& size_in)
      : pose(pose_in), size(size_in) {}

  /// A finite pose with a proper rotation and finite, strictly positive sides.
  bool is_valid() const;
  double volume() const { return size.prod(); }
  Eigen::Vector3d center() const { return pose.translation(); }

  /// Closed containment: points on a face are inside.
  bool contains(const Eigen::Vector3d& p) const;
  bool contains(const Eigen::Vector3f& p) const { return contains(p.cast<double>().eval()); }

  /// The 8 corners; corner i has offset (+-sx/2, +-sy/2, +-sz/2) with bit 0 (x), 1 (y), 2 (z) of
  /// i set for the + sign.
  std::array<Eigen::Vector3d, 8> corners() const;

  /// The same box expressed in another frame: given T_new_frame, returns pose T_new_frame * pose.
  Box transformed(const Eigen::Isometry3d& T_new_frame) const;
};

}  // namespace lmk
