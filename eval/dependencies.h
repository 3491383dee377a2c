// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::eval: datasets, the simulated depth sensor and scene generator, metrics.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// nlohmann-json (dataset files) and CGAL (ray casting in the simulated sensor).
std::vector<DependencyVersion> eval_dependencies();

}  // namespace lmk
