// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/dependencies.h"

#include <CGAL/version.h>
#include <oneapi/tbb/version.h>
#include <pcl/pcl_config.h>

#include <Eigen/Core>
#include <nanoflann.hpp>

namespace lmk {

std::string dotted_version(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

std::vector<DependencyVersion> geometry_dependencies() {
  return {
      {"Eigen", dotted_version(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"PCL", PCL_VERSION_PRETTY},
      {"CGAL", CGAL_VERSION_STR},
      {"nanoflann", dotted_version(NANOFLANN_VERSION >> 8, (NANOFLANN_VERSION >> 4) & 0xf,
                                   NANOFLANN_VERSION & 0xf)},
      {"oneTBB", std::to_string(TBB_VERSION_MAJOR) + "." + std::to_string(TBB_VERSION_MINOR)},
  };
}

}  // namespace lmk
