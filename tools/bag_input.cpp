// SPDX-License-Identifier: BSD-3-Clause
#include "tools/bag_input.h"

#include <filesystem>

namespace lmk::cli {

bool is_bag(const std::string& path) { return std::filesystem::path(path).extension() == ".bag"; }

void add_bag_options(CLI::App* sub, BagOptions& options, bool with_time) {
  sub->add_option("--topic", options.topic,
                  "With a bag: the PointCloud2 topic (default: the bag's only one)");
  if (with_time) {
    sub->add_option("--time", options.time,
                    "With a bag: seconds from its start; the frame recorded nearest is used")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
  }
  sub->add_option("--frame", options.frame,
                  "With a bag: the TF frame to express the scene in (default: base_link when the "
                  "bag's TF has it, else the camera's frame)");
}

}  // namespace lmk::cli
