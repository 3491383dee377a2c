// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/dependencies.h"

#include <pcl/pcl_config.h>

namespace lmk {

std::vector<DependencyVersion> landmark_dependencies() { return {{"PCL", PCL_VERSION_PRETTY}}; }

}  // namespace lmk
