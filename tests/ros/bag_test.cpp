// SPDX-License-Identifier: BSD-3-Clause
// ROS bags as lmk input: a bag this test writes (three noisy frames of a rendered tabletop in the
// camera's optical frame, and TF placing the camera in base_link) is read back by `lmk find
// --topic --time`, `lmk info` and `lmk gen --from-bag`. No ROS master is involved: bags are files.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <sys/stat.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lmk/datasets/dataset.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/ros/cloud_conversion.h"
#include "lmk/ros/latest_frame.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"
#include "tests/ros/support/ros_harness.h"
#include "tests/support/test_support.h"

namespace lmk::test {
namespace {

constexpr const char* kTopic = "/head_mount_kinect/depth_registered/points";
constexpr const char* kOptical = "head_mount_kinect_rgb_optical_frame";
const ::ros::Time kStart(1700000000, 0);

/// A session: three frames of one tabletop, each with its own depth noise, one second apart, and
/// the camera's pose on /tf_static; plus the carton captured from the first frame.
struct Session {
  ScratchDir dir;
  std::string bag, landmark;
  std::vector<sensor_msgs::PointCloud2> clouds;
  geometry_msgs::TransformStamped camera;

  Session() {
    const SyntheticScene scene = make_tabletop_scene(3);
    camera = tf2::eigenToTransform(scene.T_world_sensor);
    camera.header.frame_id = "base_link";
    camera.header.stamp = kStart;
    camera.child_frame_id = kOptical;
    rosbag::Bag out(dir.file("session.bag"), rosbag::bagmode::Write);
    tf2_msgs::TFMessage tf;
    tf.transforms.push_back(camera);
    out.write("/tf_static", kStart, tf);
    for (int k = 0; k < 3; ++k) {
      DepthSensorSettings sensor;
      sensor.seed = 10 + k;
      const PointCloud world = render_depth(scene.mesh, scene.T_world_sensor, sensor);
      if (k == 0) {
        CaptureSettings capture;
        capture.base_frame = true;
        const Landmark carton = lmk::capture(world, scene.objects.front().box, "carton", capture);
        landmark = dir.file("carton.lmk");
        save_landmark(landmark, carton);
      }
      sensor_msgs::PointCloud2 msg =
          ros1::to_ros(world.transformed(scene.T_world_sensor.inverse()), kOptical);
      msg.header.stamp = kStart + ::ros::Duration(k);
      out.write(kTopic, msg.header.stamp, msg);
      clouds.push_back(msg);
    }
    out.write("/chatter", kStart + ::ros::Duration(2.5), camera);  // another topic, not a cloud
    bag = dir.file("session.bag");
  }
};

const Session& session() {
  static const Session* s = new Session;
  return *s;
}

std::pair<int, std::string> run_lmk(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), LMK_BINARY);
  return run_to_end(args, dir.file("lmk.log"));
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// The scene frames of the session's clouds, as `lmk find` reads them from the bag: in base_link
/// with the camera's pose from TF.
ros1::Frame session_frame(std::size_t k) {
  ::ros::Time::init();
  tf2_ros::Buffer tf;
  tf.setTransform(session().camera, "test", true);
  return ros1::frame_from_cloud(session().clouds.at(k), tf, "base_link", "", ::ros::Duration(0));
}

TEST(Bags, FindOnABagFrameEqualsFindOnThatFrameInTheBaseFrame) {
  const Session& s = session();
  const ScratchDir dir;
  // The frame recorded nearest 1.3 s is the second; TF from the bag puts it in base_link.
  const auto [code, out] = run_lmk(dir, {"find", s.bag, s.landmark, "--topic", kTopic, "--time",
                                         "1.3", "--json", dir.file("bag.json")});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("in base_link"), std::string::npos) << out;

  write_cloud(dir.file("frame.pcd"), session_frame(1).scene);
  const auto [code2, out2] = run_lmk(dir, {"find", dir.file("frame.pcd"), s.landmark,
                                           "--base-frame", "--json", dir.file("pcd.json")});
  ASSERT_EQ(code2, 0) << out2;
  nlohmann::json from_bag = read_json(dir.file("bag.json"))["matches"];
  nlohmann::json from_pcd = read_json(dir.file("pcd.json"))["matches"];
  ASSERT_FALSE(from_bag.empty());
  ASSERT_EQ(from_bag.size(), from_pcd.size());
  // The same matches. Their confidences agree to the precision of the sensor pose, which the PCD
  // file's VIEWPOINT keeps in single precision: the range, and so the error's sigma, differ by
  // micrometres.
  for (std::size_t i = 0; i < from_bag.size(); ++i) {
    EXPECT_NEAR(from_bag[i]["confidence"]["probability"].get<double>(),
                from_pcd[i]["confidence"]["probability"].get<double>(), 1e-5);
    EXPECT_NEAR(from_bag[i]["confidence"]["range"].get<double>(),
                from_pcd[i]["confidence"]["range"].get<double>(), 1e-4);
    from_bag[i].erase("confidence");
    from_pcd[i].erase("confidence");
  }
  EXPECT_EQ(from_bag, from_pcd);

  // Another frame gives other matches (its own noise): the time chose the frame.
  const auto [code3, out3] =
      run_lmk(dir, {"find", s.bag, s.landmark, "--time", "0", "--json", dir.file("first.json")});
  ASSERT_EQ(code3, 0) << out3;
  EXPECT_NE(read_json(dir.file("first.json"))["matches"],
            read_json(dir.file("bag.json"))["matches"]);
}

TEST(Bags, FramesOfABagAreFusedAsTheSameFramesFromFiles) {
  const Session& s = session();
  const ScratchDir dir;
  // --frames 2 from 0.8 s: the second and third clouds.
  const auto [code, out] = run_lmk(dir, {"find", s.bag, s.landmark, "--time", "0.8", "--frames",
                                         "2", "--json", dir.file("bag.json")});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("2 frames stamped 1700000001.000 to 1700000002.000 s"), std::string::npos)
      << out;
  EXPECT_NE(out.find("2 frames fused into one"), std::string::npos) << out;

  for (std::size_t k : {1u, 2u}) {
    write_cloud(dir.file("frame" + std::to_string(k) + ".pcd"), session_frame(k).scene);
  }
  const auto [code2, out2] =
      run_lmk(dir, {"find", dir.file("frame1.pcd"), dir.file("frame2.pcd"), s.landmark,
                    "--base-frame", "--json", dir.file("pcd.json")});
  ASSERT_EQ(code2, 0) << out2;
  const nlohmann::json from_bag = read_json(dir.file("bag.json"))["matches"];
  const nlohmann::json from_pcd = read_json(dir.file("pcd.json"))["matches"];
  ASSERT_FALSE(from_bag.empty());
  ASSERT_EQ(from_bag.size(), from_pcd.size());
  // The same matches, to the precision of the sensor pose a PCD's VIEWPOINT keeps (single).
  for (std::size_t i = 0; i < from_bag.size(); ++i) {
    const std::vector<double> a = from_bag[i]["position"];
    const std::vector<double> b = from_pcd[i]["position"];
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(a[d], b[d], 1e-4) << "match " << i;
  }

  // A window of 1.5 s from the first cloud holds the first two.
  const auto [code3, out3] =
      run_lmk(dir, {"find", s.bag, s.landmark, "--time-window", "1.5", "--json", "-"});
  ASSERT_EQ(code3, 0) << out3;
  EXPECT_NE(out3.find("2 frames stamped 1700000000.000 to 1700000001.000 s"), std::string::npos)
      << out3;
}

TEST(Bags, FramesAreChosenFromOneBagOnly) {
  const Session& s = session();
  const ScratchDir dir;
  write_cloud(dir.file("frame.pcd"), session_frame(0).scene);
  write_text(dir.file("poses.txt"), "0 0 0 0 0 0 1\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"find", dir.file("frame.pcd"), s.landmark, "--frames", "2"},
       "--frames and --time-window choose frames of one bag"},
      {{"find", s.bag, s.landmark, "--poses", dir.file("poses.txt")},
       "a bag's frames are placed by its own TF"},
      {{"find", s.bag, dir.file("frame.pcd"), s.landmark},
       "a bag cannot be fused with other files"},
      {{"find", s.bag, s.landmark, "--frames", "31"}, "--frames"},
  };
  for (const auto& [args, reason] : cases) {
    const auto [code, out] = run_lmk(dir, args);
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find(reason), std::string::npos) << out;
  }
}

// Issue #48: lmk track reads a bag's frames one at a time, in base_link from the bag's TF, and
// follows the landmark through them as through the same frames as files.
TEST(Bags, TrackFollowsALandmarkThroughABagsFrames) {
  const Session& s = session();
  const ScratchDir dir;
  const auto [code, out] = run_lmk(dir, {"track", s.bag, s.landmark, "--json", "-"});
  ASSERT_EQ(code, 0) << out;
  std::vector<nlohmann::json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.front() == '{') lines.push_back(nlohmann::json::parse(line));
  }
  ASSERT_EQ(lines.size(), 3u) << out;
  EXPECT_EQ(lines[0]["state"], "found");
  EXPECT_EQ(lines[0]["file"], "session.bag#0");
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_EQ(lines[k]["state"], "tracking") << k;
    const std::vector<double> a = lines[0]["position"], b = lines[k]["position"];
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(a[d], b[d], 0.005) << "frame " << k;
  }
  EXPECT_NE(out.find("tracked 3 frames"), std::string::npos) << out;

  // From 0.8 s on: the last two frames; a bag with other frames is refused.
  const auto [code2, out2] = run_lmk(dir, {"track", s.bag, s.landmark, "--time", "0.8"});
  ASSERT_EQ(code2, 0) << out2;
  EXPECT_NE(out2.find("tracked 2 frames"), std::string::npos) << out2;
  write_cloud(dir.file("frame.pcd"), session_frame(0).scene);
  const auto [code3, out3] = run_lmk(dir, {"track", s.bag, dir.file("frame.pcd"), s.landmark});
  EXPECT_EQ(code3, 2) << out3;
  EXPECT_NE(out3.find("give one bag, or cloud files"), std::string::npos) << out3;
}

TEST(Bags, InfoListsTopicsTfFramesAndDuration) {
  const ScratchDir dir;
  const auto [code, out] = run_lmk(dir, {"info", session().bag, "--json"});
  ASSERT_EQ(code, 0) << out;
  const nlohmann::json info = nlohmann::json::parse(out);
  EXPECT_NEAR(info["duration"].get<double>(), 2.5, 1e-9);
  ASSERT_EQ(info["topics"].size(), 3u);
  EXPECT_EQ(info["topics"][1]["name"], kTopic);
  EXPECT_EQ(info["topics"][1]["type"], "sensor_msgs/PointCloud2");
  EXPECT_EQ(info["topics"][1]["messages"], 3);
  EXPECT_EQ(info["frames"], (nlohmann::json{"base_link", kOptical}));
}

TEST(Bags, GenFromBagWritesADatasetOfItsFrames) {
  const ScratchDir dir;
  const auto [code, out] = run_lmk(dir, {"gen", dir.file("dataset"), "--from-bag", session().bag,
                                         "--landmark", session().landmark, "--stride", "2"});
  ASSERT_EQ(code, 0) << out;
  const Dataset dataset = load_dataset(dir.file("dataset"));
  ASSERT_EQ(dataset.scenes.size(), 2u);  // frames 0 and 2
  EXPECT_EQ(dataset.scenes[1].name, "frame-00002");
  ASSERT_TRUE(dataset.scenes[0].up);
  EXPECT_TRUE(dataset.scenes[0].up->isApprox(Eigen::Vector3d::UnitZ()));
  ASSERT_EQ(dataset.landmarks.size(), 1u);
  EXPECT_EQ(dataset.landmarks[0].name, "carton");
}

TEST(Bags, BadBagsAndTopicsAreRefusedWithTheReason) {
  const ScratchDir dir;
  write_text(dir.file("fake.bag"), "not a bag at all\n");
  const auto [code, out] = run_lmk(dir, {"find", dir.file("fake.bag"), session().landmark});
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("is not a readable ROS bag"), std::string::npos) << out;
  // A named pipe waits forever for a writer: refused as a special file before any open.
  ASSERT_EQ(::mkfifo(dir.file("pipe.bag").c_str(), 0600), 0);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"find", dir.file("pipe.bag"), session().landmark},
        std::vector<std::string>{"info", dir.file("pipe.bag")},
        std::vector<std::string>{"gen", dir.file("ds2"), "--from-bag", dir.file("pipe.bag"),
                                 "--landmark", session().landmark}}) {
    const auto [fifo_code, fifo_out] = run_lmk(dir, args);
    EXPECT_EQ(fifo_code, 2) << args[0] << ": " << fifo_out;
    EXPECT_NE(fifo_out.find("pipe.bag: is a named pipe, not a ROS bag"), std::string::npos)
        << args[0] << ": " << fifo_out;
  }

  const auto [code3, out3] = run_lmk(dir, {"gen", dir.file("ds"), "--from-bag", session().bag});
  EXPECT_EQ(code3, 2) << out3;
  EXPECT_NE(out3.find("gen --from-bag: name the landmarks with --landmark FILE"), std::string::npos)
      << out3;

  const auto [code2, out2] =
      run_lmk(dir, {"find", session().bag, session().landmark, "--topic", "/chatter"});
  EXPECT_EQ(code2, 2) << out2;
  EXPECT_NE(out2.find(std::string("no PointCloud2 topic '/chatter' (it has ") + kTopic + ")"),
            std::string::npos)
      << out2;
}

}  // namespace
}  // namespace lmk::test
