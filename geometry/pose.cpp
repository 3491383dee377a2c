// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/pose.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lmk/geometry/error.h"

namespace lmk {

Eigen::Isometry3d pose_from_xyz_rpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = xyz;
  return T;
}

Eigen::Isometry3d pose_from_position_quaternion(const Eigen::Vector3d& position,
                                                const Eigen::Quaterniond& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = position;
  return T;
}

void check_translation(const Eigen::Vector3d& t, const std::string& where) {
  if (!(t.norm() <= kMaxTranslation)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", t.norm());
    throw Error(where + ": the position is " + text + " m from the origin (at most " +
                std::to_string(static_cast<int>(kMaxTranslation)) +
                " m: metres, not millimetres?)");
  }
}

Eigen::Isometry3d pose_from_unit_quaternion(const Eigen::Vector3d& position,
                                            const Eigen::Vector4d& wxyz, const std::string& where,
                                            const std::string& field) {
  if (!position.allFinite() || !wxyz.allFinite())
    throw Error(where + ": holds a non-finite number");
  check_translation(position, where);
  if (std::abs(wxyz.norm() - 1.0) > 1e-3) {
    throw Error(where + "." + field + ": is not a unit quaternion [w, x, y, z] (norm " +
                std::to_string(wxyz.norm()) + ")");
  }
  return pose_from_position_quaternion(position,
                                       Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]));
}

Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R) {
  // R = Rz(y) Ry(p) Rx(r): R(2,0) = -sin(p); away from gimbal lock r and y follow from row 2 and
  // column 0. At gimbal lock only r - y (or r + y) is defined, so roll takes it and yaw is 0.
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  if (std::abs(R(2, 0)) < 1.0 - 1e-9) {
    return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
  }
  return {std::atan2(-R(1, 2), R(1, 1)), pitch, 0.0};
}

double rotation_angle_between(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b) {
  const double c = ((R_a.transpose() * R_b).trace() - 1.0) / 2.0;
  return std::acos(std::clamp(c, -1.0, 1.0));
}

bool is_valid_pose(const Eigen::Isometry3d& T, double tolerance) {
  if (!T.matrix().allFinite() || !(T.translation().norm() <= kMaxTranslation)) return false;
  const Eigen::Matrix3d R = T.linear();
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < tolerance &&
         R.determinant() > 0.0;
}

Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  out.translation() = T.translation();
  return out;
}

}  // namespace lmk

namespace lmk {

Eigen::Isometry3d camera_look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                 const Eigen::Vector3d& up) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(up).normalized();  // right in the image
  const Eigen::Vector3d y = z.cross(x);                // down in the image
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = y;
  T.linear().col(2) = z;
  T.translation() = eye;
  return T;
}

}  // namespace lmk
