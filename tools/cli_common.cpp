#include "tools/cli_common.h"

#include <cmath>

#include "geometry/pose.h"

namespace lmk::cli {

Eigen::Vector3d rpy_degrees(const Eigen::Matrix3d& R) {
  Eigen::Vector3d rpy = rpy_from_rotation(R) * 180.0 / M_PI;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(rpy[i]) < 0.005) rpy[i] = 0.0;
  }
  return rpy;
}

}  // namespace lmk::cli
