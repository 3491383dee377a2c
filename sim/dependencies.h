// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::sim: the synthetic world and its simulated depth sensor.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// CGAL (ray casting in the simulated sensor).
std::vector<DependencyVersion> sim_dependencies();

}  // namespace lmk
