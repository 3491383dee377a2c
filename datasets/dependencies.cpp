// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/dependencies.h"

#include <nlohmann/json.hpp>

namespace lmk {

std::vector<DependencyVersion> datasets_dependencies() {
  return {{"nlohmann-json", dotted_version(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                           NLOHMANN_JSON_VERSION_PATCH)}};
}

}  // namespace lmk
