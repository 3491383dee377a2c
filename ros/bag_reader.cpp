// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/bag_reader.h"

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"

namespace lmk::ros1 {
namespace {

constexpr const char* kCloudType = "sensor_msgs/PointCloud2";

void open_bag(rosbag::Bag& bag, const std::string& path) {
  // A FIFO named x.bag hung lmk find, info and gen --from-bag in rosbag's open (issue #34,
  // finding 5): the one check every input file passes first.
  check_input_file(path, kBagInput);
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw Error(path + ": is not a readable ROS bag (" + e.what() + ")");
  }
}

/// The bag's topics with their types and message counts, sorted by name, and its time span.
void read_topics(rosbag::Bag& bag, BagSummary& summary) {
  rosbag::View view(bag);
  if (view.size() == 0) return;
  summary.start = view.getBeginTime().toSec();
  summary.end = view.getEndTime().toSec();
  std::map<std::string, BagTopic> topics;
  for (const rosbag::ConnectionInfo* c : view.getConnections()) {
    BagTopic& t = topics[c->topic];
    t.name = c->topic;
    t.type = c->datatype;
  }
  for (auto& [name, topic] : topics) {
    rosbag::View one(bag, rosbag::TopicQuery(name));
    topic.messages = one.size();
    summary.topics.push_back(topic);
  }
}

/// The bag's whole TF history, for lookups at any recorded stamp.
void load_tf(rosbag::Bag& bag, tf2_ros::Buffer& tf) {
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& m : view) {
    const auto msg = m.instantiate<tf2_msgs::TFMessage>();
    if (!msg) continue;
    const bool is_static = m.getTopic() == "/tf_static";
    for (const geometry_msgs::TransformStamped& t : msg->transforms) {
      tf.setTransform(t, "bag", is_static);
    }
  }
}

/// The bag opened once for reading frames: its topics, the cloud topic chosen, and its TF.
struct OpenBag {
  rosbag::Bag bag;
  BagSummary summary;  // topics and time span; frames are not collected
  std::string topic;
  std::unique_ptr<tf2_ros::Buffer> tf;

  OpenBag(const std::string& path, const BagFrameOptions& options) {
    open_bag(bag, path);
    read_topics(bag, summary);
    topic = bag_cloud_topic(summary, path, options.topic);
    // ros::Time drives tf2_ros's lookups, even with no ROS master: wall time is enough here.
    if (!::ros::Time::isValid()) ::ros::Time::init();
    tf = std::make_unique<tf2_ros::Buffer>(::ros::Duration(summary.duration() + 60.0));
    load_tf(bag, *tf);
  }

  /// Calls f(time from the bag's start, message) for each cloud of the topic, in record order,
  /// until f returns false.
  template <class F>
  void for_each_cloud(F&& f) {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto msg = m.instantiate<sensor_msgs::PointCloud2>();
      if (msg && !f(m.getTime().toSec() - summary.start, *msg)) return;
    }
  }

  Frame frame(const sensor_msgs::PointCloud2& msg, const BagFrameOptions& options) const {
    std::string target = options.target_frame.empty() ? msg.header.frame_id : options.target_frame;
    if (options.target_frame_optional && !tf->_frameExists(target)) target = msg.header.frame_id;
    return frame_from_cloud(msg, *tf, target, options.sensor_frame, ::ros::Duration(0));
  }
};

}  // namespace

BagSummary summarize_bag(const std::string& path) {
  rosbag::Bag bag;
  open_bag(bag, path);
  BagSummary summary;
  read_topics(bag, summary);
  std::set<std::string> frames;
  rosbag::View tf(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& m : tf) {
    if (const auto msg = m.instantiate<tf2_msgs::TFMessage>()) {
      for (const auto& t : msg->transforms) {
        frames.insert(t.header.frame_id);
        frames.insert(t.child_frame_id);
      }
    }
  }
  summary.frames.assign(frames.begin(), frames.end());
  return summary;
}

std::string bag_cloud_topic(const BagSummary& bag, const std::string& path,
                            const std::string& topic) {
  std::vector<std::string> clouds;
  for (const BagTopic& t : bag.topics) {
    if (t.type == kCloudType) clouds.push_back(t.name);
  }
  std::string list;
  for (const std::string& c : clouds) list += (list.empty() ? "" : ", ") + c;
  if (!topic.empty()) {
    if (std::find(clouds.begin(), clouds.end(), topic) != clouds.end()) return topic;
    throw Error(path + ": no PointCloud2 topic '" + topic + "' (it has " +
                (list.empty() ? "none" : list) + ")");
  }
  if (clouds.size() == 1) return clouds.front();
  throw Error(path + (clouds.empty() ? ": holds no PointCloud2 topic"
                                     : ": holds several PointCloud2 topics; choose one with "
                                       "--topic (" +
                                           list + ")"));
}

std::vector<Frame> read_bag_frames_at(const std::string& path, const BagFrameOptions& options,
                                      double seconds, std::size_t count, double window) {
  if (count == 0) throw Error("at least one bag frame must be read");
  OpenBag open(path, options);
  // Record times increase: the nearest cloud is the last one whose distance to `seconds` still
  // shrank. Clouds are kept from there on, until `count` or the window's end.
  std::vector<std::pair<double, sensor_msgs::PointCloud2>> kept;
  double best = std::numeric_limits<double>::infinity();
  open.for_each_cloud([&](double t, const sensor_msgs::PointCloud2& msg) {
    const bool nearer = std::abs(t - seconds) < best;
    if (nearer && kept.size() <= 1) {
      // Still approaching `seconds`: this cloud replaces the candidate for the first.
      best = std::abs(t - seconds);
      kept.assign(1, {t, msg});
      return true;
    }
    if (window > 0.0 && t - kept.front().first > window) return false;
    kept.emplace_back(t, msg);
    return kept.size() < count;
  });
  if (kept.empty()) throw Error(path + ": no cloud on " + open.topic);
  if (kept.size() > count) kept.resize(count);
  std::vector<Frame> frames;
  for (const auto& [t, msg] : kept) {
    try {
      frames.push_back(open.frame(msg, options));
    } catch (const Error& e) {
      char when[48];
      std::snprintf(when, sizeof when, ": the cloud of %.3f s: ", t);
      throw Error(path + when + e.what());
    }
  }
  return frames;
}

Frame read_bag_frame(const std::string& path, const BagFrameOptions& options, double seconds) {
  return read_bag_frames_at(path, options, seconds, 1).front();
}

void for_each_bag_frame(const std::string& path, const BagFrameOptions& options, double seconds,
                        std::size_t stride, const std::function<bool(const Frame&)>& visit) {
  if (stride == 0) throw Error("the stride between bag frames must be at least 1");
  OpenBag open(path, options);
  std::size_t index = 0;  // clouds from `seconds` on
  open.for_each_cloud([&](double t, const sensor_msgs::PointCloud2& msg) {
    if (t < seconds || index++ % stride != 0) return true;
    Frame frame;
    try {
      frame = open.frame(msg, options);
    } catch (const Error& e) {
      char when[48];
      std::snprintf(when, sizeof when, ": the cloud of %.3f s: ", t);
      throw Error(path + when + e.what());
    }
    return visit(frame);
  });
}

std::vector<Frame> read_bag_frames(const std::string& path, const BagFrameOptions& options,
                                   std::size_t stride) {
  std::vector<Frame> frames;
  for_each_bag_frame(path, options, 0.0, stride, [&](const Frame& f) {
    frames.push_back(f);
    return true;
  });
  return frames;
}

}  // namespace lmk::ros1
