// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Recorded sessions as lmk input (docs/ros.md, "Bags"): what a rosbag holds, and its camera frames
// moved into a frame of its TF tree with the bag's own /tf and /tf_static, as lmk_node would have
// seen them live.

#include <functional>
#include <string>
#include <vector>

#include "lmk/ros/latest_frame.h"

namespace lmk::ros1 {

struct BagTopic {
  std::string name, type;
  std::size_t messages = 0;
};

struct BagSummary {
  double start = 0.0, end = 0.0;    ///< s, the first and last message's record time
  std::vector<BagTopic> topics;     ///< sorted by name
  std::vector<std::string> frames;  ///< every frame the bag's TF names, sorted
  double duration() const { return end - start; }
};

/// Throws lmk::Error naming the file when it is no readable bag.
BagSummary summarize_bag(const std::string& path);

/// The PointCloud2 topic to read: `topic` when given (it must hold PointCloud2 messages), else the
/// bag's only PointCloud2 topic; lmk::Error naming the candidates otherwise.
std::string bag_cloud_topic(const BagSummary& bag, const std::string& path,
                            const std::string& topic);

struct BagFrameOptions {
  std::string topic;         ///< see bag_cloud_topic
  std::string target_frame;  ///< frame to express clouds in; empty: the cloud's own
  /// When the bag's TF does not know target_frame, use the cloud's own frame instead of failing.
  bool target_frame_optional = false;
  std::string sensor_frame;  ///< the camera's optical frame; empty: the cloud's own
};

/// The cloud recorded nearest `seconds` after the bag's start, as a Frame in target_frame
/// (Frame::base_frame says which frame it is in).
Frame read_bag_frame(const std::string& path, const BagFrameOptions& options, double seconds);

/// Consecutive clouds of one moment, as Frames in target_frame: from the one recorded nearest
/// `seconds` after the bag's start, `count` of them, and with `window` > 0 only those recorded
/// within `window` s of that first one. Each keeps its own sensor pose from TF at its stamp, so
/// that frames of a head that moved between them can be fused (occupancy/tsdf_volume.h).
std::vector<Frame> read_bag_frames_at(const std::string& path, const BagFrameOptions& options,
                                      double seconds, std::size_t count, double window = 0.0);

/// Every `stride`-th cloud of the topic recorded `seconds` or more after the bag's start, one at a
/// time, as a Frame in target_frame, until `visit` returns false: what a tracker follows a long
/// session with, never holding more than one of its frames.
void for_each_bag_frame(const std::string& path, const BagFrameOptions& options, double seconds,
                        std::size_t stride, const std::function<bool(const Frame&)>& visit);

/// Every `stride`-th cloud of the topic (1: all), as Frames in target_frame.
std::vector<Frame> read_bag_frames(const std::string& path, const BagFrameOptions& options,
                                   std::size_t stride = 1);

}  // namespace lmk::ros1
