// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/dependencies.h"

#include <nlohmann/json.hpp>

namespace lmk {

std::vector<DependencyVersion> pbd_dependencies() {
  return {{"nlohmann-json", dotted_version(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                           NLOHMANN_JSON_VERSION_PATCH)}};
}

}  // namespace lmk
