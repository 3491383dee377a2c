// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/dependencies.h"

namespace lmk {

std::vector<DependencyVersion> pr2_dependencies() {
  return {{"urdfdom", LMK_URDFDOM_VERSION}, {"OMPL", LMK_OMPL_VERSION}};
}

}  // namespace lmk
