// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/dependencies.h"

#include <CGAL/version.h>

namespace lmk {

std::vector<DependencyVersion> sim_dependencies() { return {{"CGAL", CGAL_VERSION_STR}}; }

}  // namespace lmk
