// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/dependencies.h"

#include <ceres/version.h>

namespace lmk {

std::vector<DependencyVersion> registration_dependencies() {
  return {{"Ceres", CERES_VERSION_STRING}};
}

}  // namespace lmk
