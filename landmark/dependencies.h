// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::landmark: landmark model, storage, metrics and search.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// PCL (the paper-faithful reference search runs PCL's ICP) and OpenVDB (.lmk files).
std::vector<DependencyVersion> landmark_dependencies();

}  // namespace lmk
