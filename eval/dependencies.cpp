// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/dependencies.h"

#include <CGAL/version.h>

#include <nlohmann/json.hpp>

namespace lmk {

std::vector<DependencyVersion> eval_dependencies() {
  return {{"nlohmann-json", dotted_version(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                           NLOHMANN_JSON_VERSION_PATCH)},
          {"CGAL", CGAL_VERSION_STR}};
}

}  // namespace lmk
