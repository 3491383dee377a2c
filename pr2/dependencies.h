// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::pr2: PR2 model from URDF, kinematics and a simulated PR2.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// urdfdom (the version CMake found; urdfdom has no version macro).
std::vector<DependencyVersion> pr2_dependencies();

}  // namespace lmk
