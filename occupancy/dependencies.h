// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::occupancy: OpenVDB distance fields, empty-space and occupancy grids.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// OpenVDB.
std::vector<DependencyVersion> occupancy_dependencies();

}  // namespace lmk
