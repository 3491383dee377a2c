// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/dependencies.h"

#include <openvdb/version.h>

namespace lmk {

std::vector<DependencyVersion> occupancy_dependencies() {
  return {{"OpenVDB", OPENVDB_LIBRARY_VERSION_STRING}};
}

}  // namespace lmk
