// SPDX-License-Identifier: BSD-3-Clause
#include "tools/bag_input.h"

#include <filesystem>

#include "lmk/occupancy/tsdf_volume.h"
#include "tools/cli_common.h"

namespace lmk::cli {

bool is_bag(const std::string& path) { return std::filesystem::path(path).extension() == ".bag"; }

void add_bag_options(CLI::App* sub, BagOptions& options, bool with_time) {
  sub->add_option("--topic", options.topic,
                  "With a bag: the PointCloud2 topic (default: the bag's only one)");
  if (with_time) {
    sub->add_option("--time", options.time,
                    "With a bag: seconds from its start; the frame recorded nearest is used")
        ->check(within(0.0, 1e6))  // eleven days of a recording
        ->capture_default_str();
    sub->add_option("--frames", options.frames,
                    "With a bag: fuse this many consecutive frames from that one into the scene "
                    "(each placed by the bag's TF at its stamp; default 1)")
        ->check(CLI::Range(std::size_t{1}, kMaxFusedFrames));
    sub->add_option("--time-window", options.time_window,
                    "With a bag: fuse the frames recorded within this many seconds of that one "
                    "(at most --frames, or " +
                        std::to_string(kMaxFusedFrames) + " without it)")
        ->check(within(0.0, 60.0));
  }
  sub->add_option("--frame", options.frame,
                  "With a bag: the TF frame to express the scene in (default: base_link when the "
                  "bag's TF has it, else the camera's frame)");
}

}  // namespace lmk::cli
