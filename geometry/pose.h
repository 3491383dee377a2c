// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Pose helpers on Eigen::Isometry3d. Names carry frames: T_a_b maps coordinates in frame b to
// frame a. Angles are radians; roll/pitch/yaw are the URDF convention, R = Rz(yaw) Ry(pitch)
// Rx(roll).

#include <Eigen/Geometry>
#include <string>

namespace lmk {

Eigen::Isometry3d pose_from_xyz_rpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);
Eigen::Isometry3d pose_from_position_quaternion(const Eigen::Vector3d& position,
                                                const Eigen::Quaterniond& q);
/// The same from a pose read from a file or the wire: `wxyz` is [w, x, y, z] and must have unit
/// length within 1e-3 (what text and wire formats keep). Throws lmk::Error as "<where>: holds a
/// non-finite number" or "<where>.<field>: is not a unit quaternion [w, x, y, z] (norm N)".
Eigen::Isometry3d pose_from_unit_quaternion(const Eigen::Vector3d& position,
                                            const Eigen::Vector4d& wxyz, const std::string& where,
                                            const std::string& field);
/// Roll, pitch, yaw of a rotation, with pitch in [-pi/2, pi/2].
Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R);
/// Angle in [0, pi] of the relative rotation R_a^T R_b.
double rotation_angle_between(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b);
/// The farthest a pose may place anything from its frame's origin, m: ten kilometres is beyond any
/// scene a depth camera sees, and 1e308 made every later product overflow (issue #47).
inline constexpr double kMaxTranslation = 1e4;

/// Throws lmk::Error (`where` first) for a translation farther than kMaxTranslation (or NaN).
void check_translation(const Eigen::Vector3d& t, const std::string& where);

/// True when every coefficient is finite, the translation within kMaxTranslation and the linear
/// part a rotation within `tolerance`.
bool is_valid_pose(const Eigen::Isometry3d& T, double tolerance = 1e-6);
/// The k-th (from 0) of a pattern that alternates either side of where it starts, one step further
/// each time: 0, +1, -1, +2, -2, ... (a head panning about its first view between looks).
inline int alternating_step(int k) { return (k + 1) / 2 * (k % 2 == 1 ? 1 : -1); }
/// The nearest proper rigid transform (through a normalised quaternion): rotations composed over
/// many steps, or built in float, drift from orthonormality by a few 1e-6.
Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& T);

}  // namespace lmk

namespace lmk {

/// Pose T_world_camera of a camera at `eye` looking at `target`, in the optical convention of depth
/// sensors: z forward, x right, y down in the image. `up` is the world's up direction; it must not
/// be parallel to the viewing direction.
Eigen::Isometry3d camera_look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                 const Eigen::Vector3d& up);

}  // namespace lmk
