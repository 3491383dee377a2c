// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// ROS bags as lmk CLI input (docs/ros.md, "Bags"): `lmk find BAG ...`, `lmk info BAG` and
// `lmk gen --from-bag BAG`. Built with ROS 1 they read the bag; without it they refuse with the
// reason (tools/bag_input_no_ros.cpp).

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk::cli {

/// Whether `path` names a ROS bag (by its .bag extension).
bool is_bag(const std::string& path);

struct BagOptions {
  std::string topic;  ///< the PointCloud2 topic; empty: the bag's only one
  double time = 0.0;  ///< s from the bag's start: the frame recorded nearest it
  /// Consecutive frames from that one, fused into one scene (occupancy/tsdf_volume.h): at most
  /// `frames` (0: one, or with a window as many as one fusion takes), and with `time_window` > 0
  /// only those recorded within it of the first.
  std::size_t frames = 0;
  double time_window = 0.0;  ///< s; 0: no window
  /// Whether more than the one frame nearest `time` may be read.
  bool several() const { return frames > 1 || time_window > 0.0; }
  std::string frame;  ///< frame to search in; empty: base_link when the bag's TF has it
};
void add_bag_options(CLI::App* sub, BagOptions& options, bool with_time);

/// The frames of the bag that options.time, frames and time_window name (one by default: the frame
/// nearest options.time), in options.frame (or base_link, or the cloud's own frame when the bag's
/// TF has no base_link), each with its sensor pose from TF. `in_base_frame` says whether they are
/// in base_link, whose +z is up.
std::vector<PointCloud> read_bag_scenes(const std::string& path, const BagOptions& options,
                                        bool& in_base_frame);

/// The bag's frames from options.time on, one at a time and in order (options.frame, or base_link
/// when the bag's TF has it, else the cloud's own frame), each with its sensor pose from TF, until
/// `visit` returns false: what lmk track follows a recorded session with. `visit` also hears
/// whether the frame is in base_link, whose +z is up.
void for_each_bag_scene(const std::string& path, const BagOptions& options,
                        const std::function<bool(PointCloud& scene, bool in_base_frame)>& visit);

/// lmk info on a bag: its duration, topics with their types and counts, and TF frames.
int print_bag_info(const std::string& path, bool json);

/// lmk gen --from-bag: a dataset of every `stride`-th frame of the bag (scenes in the base frame
/// when TF has it) with the given landmarks and no labelled instance yet.
int write_bag_dataset(const std::string& path, const BagOptions& options, std::size_t stride,
                      const std::vector<std::string>& landmarks, const std::string& output);

}  // namespace lmk::cli
