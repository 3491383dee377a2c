// SPDX-License-Identifier: BSD-3-Clause
// Bags in a build without ROS 1: recognised, and refused with the reason.
#include "lmk/geometry/error.h"
#include "tools/bag_input.h"

namespace lmk::cli {
namespace {

[[noreturn]] void no_ros(const std::string& path) {
  throw Error(path +
              ": reading ROS bags needs lmk built with ROS 1 (LMK_WITH_ROS=ON after "
              "scripts/install-deps.sh)");
}

}  // namespace

std::vector<PointCloud> read_bag_scenes(const std::string& path, const BagOptions&, bool&) {
  no_ros(path);
}
void for_each_bag_scene(const std::string& path, const BagOptions&,
                        const std::function<bool(PointCloud&, bool)>&) {
  no_ros(path);
}
int print_bag_info(const std::string& path, bool) { no_ros(path); }
int write_bag_dataset(const std::string& path, const BagOptions&, std::size_t,
                      const std::vector<std::string>&, const std::string&) {
  no_ros(path);
}

}  // namespace lmk::cli
