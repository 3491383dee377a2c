// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::registration: ICP and Ceres robust refinement on SE(3).
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// Ceres.
std::vector<DependencyVersion> registration_dependencies();

}  // namespace lmk
