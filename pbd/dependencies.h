// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::pbd: programs, recording and safe execution through RobotInterface.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// nlohmann-json (program files).
std::vector<DependencyVersion> pbd_dependencies();

}  // namespace lmk
