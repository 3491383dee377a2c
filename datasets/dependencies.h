// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk::datasets: dataset files, their generators and importers.
// Its dependency report: the libraries this module is built on, with their compiled-in versions.

#include "lmk/geometry/dependencies.h"

namespace lmk {

/// nlohmann-json (dataset files, sequences, poses).
std::vector<DependencyVersion> datasets_dependencies();

}  // namespace lmk
