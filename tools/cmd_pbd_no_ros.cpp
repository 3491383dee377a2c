// SPDX-License-Identifier: BSD-3-Clause
// lmk pbd run --ros in a build without ROS 1.
#include "lmk/geometry/error.h"
#include "tools/pbd_common.h"

namespace lmk::cli {

int run_on_ros(const PbdOptions&) {
  throw Error(
      "pbd run --ros: this lmk was built without ROS 1 (configure with LMK_WITH_ROS=ON "
      "after scripts/install-deps.sh)");
}

}  // namespace lmk::cli
