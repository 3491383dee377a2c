// SPDX-License-Identifier: BSD-3-Clause
// Bags through lmk::ros's reader (ros/bag_reader.h).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "lmk/datasets/dataset.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/ros/bag_reader.h"
#include "tools/bag_input.h"

namespace lmk::cli {
namespace {

constexpr const char* kBaseFrame = "base_link";

/// Scenes in options.frame, or by default in base_link when the bag's TF has it (+z up there),
/// else in the camera's own frame.
ros1::BagFrameOptions frame_options(const BagOptions& options) {
  ros1::BagFrameOptions out;
  out.topic = options.topic;
  out.target_frame = options.frame.empty() ? kBaseFrame : options.frame;
  out.target_frame_optional = options.frame.empty();
  return out;
}

}  // namespace

std::vector<PointCloud> read_bag_scenes(const std::string& path, const BagOptions& options,
                                        bool& in_base_frame) {
  const std::size_t count =
      options.frames > 0 ? options.frames : (options.time_window > 0.0 ? kMaxFusedFrames : 1);
  const std::vector<ros1::Frame> frames = ros1::read_bag_frames_at(
      path, frame_options(options), options.time, count, options.time_window);
  in_base_frame = frames.front().base_frame == kBaseFrame;
  const char* topic = options.topic.empty() ? "its cloud topic" : options.topic.c_str();
  if (frames.size() == 1) {
    std::fprintf(stderr, "%s: the frame of %.3f s on %s, in %s\n", path.c_str(),
                 frames.front().stamp.toSec(), topic, frames.front().base_frame.c_str());
  } else {
    std::fprintf(stderr, "%s: %zu frames stamped %.3f to %.3f s on %s, in %s\n", path.c_str(),
                 frames.size(), frames.front().stamp.toSec(), frames.back().stamp.toSec(), topic,
                 frames.front().base_frame.c_str());
  }
  std::vector<PointCloud> scenes;
  for (const ros1::Frame& f : frames) scenes.push_back(f.scene);
  return scenes;
}

void for_each_bag_scene(const std::string& path, const BagOptions& options,
                        const std::function<bool(PointCloud& scene, bool in_base_frame)>& visit) {
  ros1::for_each_bag_frame(path, frame_options(options), options.time, 1,
                           [&](const ros1::Frame& f) {
                             PointCloud scene = f.scene;
                             return visit(scene, f.base_frame == kBaseFrame);
                           });
}

int print_bag_info(const std::string& path, bool json) {
  const ros1::BagSummary bag = ros1::summarize_bag(path);
  if (json) {
    nlohmann::json topics = nlohmann::json::array();
    for (const ros1::BagTopic& t : bag.topics) {
      topics.push_back({{"name", t.name}, {"type", t.type}, {"messages", t.messages}});
    }
    std::cout << nlohmann::json({{"file", path},
                                 {"start", bag.start},
                                 {"duration", bag.duration()},
                                 {"topics", topics},
                                 {"frames", bag.frames}})
                     .dump(2)
              << "\n";
    return 0;
  }
  std::printf("file           %s\n", path.c_str());
  std::printf("format         ROS bag\n");
  std::printf("duration       %.3f s (from %.3f)\n", bag.duration(), bag.start);
  for (const ros1::BagTopic& t : bag.topics) {
    std::printf("topic          %-40s %-28s %zu messages\n", t.name.c_str(), t.type.c_str(),
                t.messages);
  }
  std::string frames;
  for (const std::string& f : bag.frames) frames += (frames.empty() ? "" : " ") + f;
  std::printf("TF frames      %s\n", frames.empty() ? "(no TF)" : frames.c_str());
  return 0;
}

int write_bag_dataset(const std::string& path, const BagOptions& options, std::size_t stride,
                      const std::vector<std::string>& landmarks, const std::string& output) {
  if (landmarks.empty()) throw Error("gen --from-bag: name the landmarks with --landmark FILE");
  namespace fs = std::filesystem;
  const std::vector<ros1::Frame> frames =
      ros1::read_bag_frames(path, frame_options(options), stride);
  if (frames.empty()) throw Error(path + ": no frame to write");
  const bool in_base_frame = frames.front().base_frame == kBaseFrame;
  fs::create_directories(fs::path(output) / "scenes");
  fs::create_directories(fs::path(output) / "landmarks");

  Dataset dataset;
  dataset.name = fs::path(path).stem().string();
  for (const std::string& file : landmarks) {
    const Landmark landmark = load_landmark(file);  // checks it before copying
    const std::string relative = "landmarks/" + landmark.name + ".lmk";
    save_landmark((fs::path(output) / relative).string(), landmark);
    dataset.landmarks.push_back({landmark.name, relative, Symmetry()});
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%05zu", i * stride);
    DatasetScene scene;
    scene.name = name;
    scene.file = std::string("scenes/") + name + ".pcd";
    scene.setting = "bag";
    scene.T_scene_sensor = frames[i].scene.T_cloud_sensor;
    if (in_base_frame) scene.up = Eigen::Vector3d::UnitZ();
    write_cloud((fs::path(output) / scene.file).string(), frames[i].scene);
    dataset.scenes.push_back(scene);
  }
  save_dataset(output, dataset);
  std::printf(
      "wrote dataset '%s' to %s: %zu frames of %s (every %zu), %zu landmarks, no labelled "
      "instances yet (docs/datasets.md: add them as pairs)\n",
      dataset.name.c_str(), output.c_str(), frames.size(), path.c_str(), stride,
      dataset.landmarks.size());
  return 0;
}

}  // namespace lmk::cli
