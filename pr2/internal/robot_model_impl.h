// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// RobotModel's parsed description, shared by the files that implement it (robot_model.cpp, the
// kinematics; robot_collision.cpp, the collision shapes).

#include <urdf_parser/urdf_parser.h>

#include <string>

#include "lmk/pr2/robot_model.h"

namespace lmk {

struct RobotModel::Impl {
  urdf::ModelInterfaceSharedPtr model;
  std::string what;  // the file or source, for messages
  std::string dir;   // the file's directory, where its meshes are looked for; empty for text
};

namespace detail {
Eigen::Isometry3d to_eigen(const urdf::Pose& pose);
}  // namespace detail

}  // namespace lmk
