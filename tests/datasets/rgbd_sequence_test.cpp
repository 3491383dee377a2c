// SPDX-License-Identifier: BSD-3-Clause
// The RGB-D importer: each layout (frames, TUM RGB-D, BOP) read from small sequences written here,
// its poses and units checked against what was written, and a clear error for each bad file; then
// the real sequences of ../shared/data/real when present.

#include "lmk/datasets/rgbd_sequence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "lmk/datasets/rgbd_dataset.h"
#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark_file.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;
using test::error_of;
using test::ScratchDir;
using test::write_text;

// A 4 x 3 depth image, every pixel at `units`.
std::string flat_depth_png(std::uint16_t units) {
  DepthImage d;
  d.width = 4;
  d.height = 3;
  d.depth.assign(12, units);
  return depth_png(d);
}

std::string matrix_text(const Eigen::Isometry3d& T) {
  std::string out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out += std::to_string(T.matrix()(r, c)) + (c < 3 ? " " : "\n");
  }
  return out;
}

const Eigen::Isometry3d kSecondPose = pose_from_xyz_rpy({0.1, -0.2, 0.3}, {0.05, 0.1, 0.4});

// The frames layout: two frames, the second moved by kSecondPose, depth in millimetres.
void write_frames_sequence(const fs::path& dir) {
  fs::create_directories(dir);
  write_text((dir / "camera-intrinsics.txt").string(), "585 0 2\n0 585 1.5\n0 0 1\n");
  write_text((dir / "frame-000000.depth.png").string(), flat_depth_png(1500));
  write_text((dir / "frame-000000.pose.txt").string(), matrix_text(Eigen::Isometry3d::Identity()));
  write_text((dir / "frame-000001.depth.png").string(), flat_depth_png(2000));
  write_text((dir / "frame-000001.pose.txt").string(), matrix_text(kSecondPose));
  write_text((dir / "frame-000001.color.png").string(),
             greyscale_png(std::vector<std::uint8_t>(12, 9), 4, 3));
}

// The depth calibration fits on the frames the dataset leaves out: with every frame used there are
// none, and the import says so instead of fitting on the frames it measures on.
TEST(RgbdSequence, CalibratingTheDepthNeedsFramesTheDatasetLeavesOut) {
  const ScratchDir dir;
  write_frames_sequence(dir.path() / "seq");
  RgbdDatasetOptions options;
  options.frame_stride = 1;
  options.calibrate_depth = true;
  try {
    generate_rgbd_dataset((dir.path() / "seq").string(), (dir.path() / "out").string(), options);
    ADD_FAILURE() << "the depth was calibrated on the frames the dataset uses";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs frames the dataset does not use"),
              std::string::npos)
        << e.what();
  }
}

// A correction is fitted or given, never both, and the import says so before reading a frame.
TEST(RgbdSequence, FittingAndGivingADepthCorrectionAtOnceIsRefused) {
  const ScratchDir dir;
  RgbdDatasetOptions options;
  options.calibrate_depth = true;
  options.depth_correction = DepthCalibration{};
  EXPECT_NE(error_of([&] {
              generate_rgbd_dataset((dir.path() / "no-such-sequence").string(),
                                    (dir.path() / "out").string(), options);
            }).find("either fit the depth correction or give one, not both"),
            std::string::npos);
}

TEST(RgbdSequence, ReadsTheFramesLayout) {
  const ScratchDir dir;
  write_frames_sequence(dir.path());
  const RgbdSequence s = read_rgbd_sequence(dir.path().string());
  EXPECT_EQ(s.layout, "frames");
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[1].name, "frame-000001");
  EXPECT_EQ(s.frames[1].intrinsics.fx, 585.0);
  EXPECT_TRUE(s.frames[1].T_world_camera.isApprox(kSecondPose, 1e-5));
  // 7-Scenes never registered colour to depth: no colour unless the caller says it is.
  EXPECT_TRUE(s.frames[1].colour_file.empty());
  const PointCloud cloud = load_rgbd_frame(s.frames[1]);
  EXPECT_EQ(cloud.width, 4u);
  EXPECT_NEAR(cloud.points[5].z(), 2.0, 1e-6);
  EXPECT_FALSE(cloud.has_colors());
  RgbdReadOptions registered;
  registered.colour_registered = true;
  const RgbdSequence coloured = read_rgbd_sequence(dir.path().string(), registered);
  EXPECT_TRUE(load_rgbd_frame(coloured.frames[1]).has_colors());
}

TEST(RgbdSequence, ReadsTumWithItsTimestampsAndDepthFactor) {
  const ScratchDir dir;
  const fs::path d = dir.path();
  fs::create_directories(d / "depth");
  fs::create_directories(d / "rgb");
  write_text((d / "intrinsics.txt").string(), "517.3 516.5 2 1.5");
  write_text((d / "depth.txt").string(),
             "# depth maps\n# file: x\n# timestamp filename\n"
             "1.000 depth/1.000.png\n2.000 depth/2.000.png\n9.000 depth/9.000.png\n");
  write_text((d / "rgb.txt").string(), "# colour\n1.010 rgb/1.010.png\n");
  // Poses at 1.005 and 2.001; none near 9 (outside the motion capture): that frame is left out.
  write_text((d / "groundtruth.txt").string(),
             "# timestamp tx ty tz qx qy qz qw\n1.005 0 0 0 0 0 0 1\n"
             "2.001 1 2 3 0 0 0.7071068 0.7071068\n");
  for (const char* t : {"1.000", "2.000", "9.000"})
    write_text((d / "depth" / (std::string(t) + ".png")).string(), flat_depth_png(5000));
  write_text((d / "rgb" / "1.010.png").string(),
             greyscale_png(std::vector<std::uint8_t>(12, 3), 4, 3));
  const RgbdSequence s = read_rgbd_sequence(d.string());
  EXPECT_EQ(s.layout, "tum");
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_NEAR(s.frames[1].T_world_camera.translation().z(), 3.0, 1e-9);
  EXPECT_NEAR(
      rotation_angle_between(s.frames[1].T_world_camera.linear(), Eigen::Matrix3d::Identity()),
      M_PI / 2, 1e-6);
  EXPECT_FALSE(s.frames[0].colour_file.empty());  // 1.010 is within 20 ms of 1.000
  EXPECT_TRUE(s.frames[1].colour_file.empty());
  const PointCloud cloud = load_rgbd_frame(s.frames[0]);
  EXPECT_NEAR(cloud.points[0].z(), 1.0, 1e-6);  // 5000 units of 1/5000 m
  EXPECT_TRUE(cloud.has_colors());
  // An associations file takes precedence, whichever of its columns comes first.
  write_text((d / "associations.txt").string(), "2.000 depth/2.000.png 1.010 rgb/1.010.png\n");
  const RgbdSequence associated = read_rgbd_sequence(d.string());
  ASSERT_EQ(associated.frames.size(), 1u);
  EXPECT_EQ(associated.frames[0].colour_file, (d / "rgb/1.010.png").string());
}

TEST(RgbdSequence, ReadsBopSceneCameras) {
  const ScratchDir dir;
  const fs::path d = dir.path();
  fs::create_directories(d / "depth");
  // The camera 0.5 m along the world's z (w2c: the world is 0.5 m behind the camera), depth in
  // tenths of a millimetre.
  write_text((d / "scene_camera.json").string(),
             R"({"3": {"cam_K": [600, 0, 2, 0, 601, 1.5, 0, 0, 1], "depth_scale": 0.1,
                        "cam_R_w2c": [1, 0, 0, 0, 1, 0, 0, 0, 1], "cam_t_w2c": [0, 0, -500]}})");
  write_text((d / "depth" / "000003.png").string(), flat_depth_png(10000));
  const RgbdSequence s = read_rgbd_sequence(d.string());
  EXPECT_EQ(s.layout, "bop");
  ASSERT_EQ(s.frames.size(), 1u);
  EXPECT_EQ(s.frames[0].intrinsics.fy, 601.0);
  EXPECT_NEAR(s.frames[0].T_world_camera.translation().z(), 0.5, 1e-12);
  EXPECT_NEAR(load_rgbd_frame(s.frames[0]).points[0].z(), 1.0, 1e-6);
}

TEST(RgbdSequence, BadFilesAndPosesAreClearErrorsNamingThem) {
  const ScratchDir dir;
  const fs::path d = dir.path() / "seq";
  const auto expect_refused = [&](const std::string& file, const std::string& expected) {
    const std::string why = error_of([&] { read_rgbd_sequence(d.string()); });
    EXPECT_NE(why.find(file), std::string::npos) << why;
    EXPECT_NE(why.find(expected), std::string::npos) << why;
  };
  fs::create_directories(d);
  expect_refused("seq", "no RGB-D frames");
  write_frames_sequence(d);
  fs::remove(d / "camera-intrinsics.txt");
  expect_refused("seq", "no intrinsics");
  write_frames_sequence(d);
  fs::remove(d / "frame-000001.pose.txt");
  expect_refused("frame-000001.pose.txt", "missing");
  write_text((d / "frame-000001.pose.txt").string(), "1 0 0 0\n0 1 0 0\n0 0 1 0\n");
  expect_refused("frame-000001.pose.txt", "12 numbers");
  write_text((d / "frame-000001.pose.txt").string(), "2 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  expect_refused("frame-000001.pose.txt", "not a rotation");
  write_text((d / "frame-000001.pose.txt").string(), "1 0 0 nan\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  expect_refused("frame-000001.pose.txt", "not finite");
  write_text((d / "frame-000001.pose.txt").string(), matrix_text(kSecondPose));
  write_text((d / "frame-000001.depth.png").string(), "garbage");
  const RgbdSequence s = read_rgbd_sequence(d.string());
  EXPECT_NE(error_of([&] { load_rgbd_frame(s.frames[1]); }).find("frame-000001.depth.png"),
            std::string::npos);

  const fs::path tum = dir.path() / "tum";
  fs::create_directories(tum);
  write_text((tum / "intrinsics.txt").string(), "500 500 2 1.5");
  write_text((tum / "depth.txt").string(), "1.0 depth/1.png\n");
  write_text((tum / "groundtruth.txt").string(), "1.0 0 0 0 0 0 0 2\n");
  EXPECT_NE(error_of([&] { read_rgbd_sequence(tum.string()); }).find("unit length"),
            std::string::npos);
  write_text((tum / "groundtruth.txt").string(), "5.0 0 0 0 0 0 0 1\n");
  EXPECT_NE(error_of([&] { read_rgbd_sequence(tum.string()); }).find("no depth frame has a pose"),
            std::string::npos);

  const fs::path bop = dir.path() / "bop";
  fs::create_directories(bop);
  write_text((bop / "scene_camera.json").string(),
             R"({"0": {"cam_K": [1, 0, 0, 0, 1, 0, 0, 0, 1]}})");
  EXPECT_NE(error_of([&] { read_rgbd_sequence(bop.string()); }).find("cam_R_w2c"),
            std::string::npos);
  write_text((bop / "scene_camera.json").string(), "{not json");
  EXPECT_NE(error_of([&] { read_rgbd_sequence(bop.string()); }).find("not valid JSON"),
            std::string::npos);
  EXPECT_NE(
      error_of([&] { read_rgbd_sequence((dir.path() / "none").string()); }).find("not a directory"),
      std::string::npos);
}

// Issue #47: the layouts hold to the rules dataset.json holds to, and agree with one another.
TEST(RgbdSequence, ListedFilesStayInsideFramesAreListedOnceAndCamerasHaveNoSkew) {
  const ScratchDir dir;
  const fs::path tum = dir.path() / "tum";
  fs::create_directories(tum / "depth");
  write_text((tum / "intrinsics.txt").string(), "500 500 2 1.5");
  write_text((tum / "groundtruth.txt").string(), "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0 1\n");
  write_text((tum / "depth" / "1.png").string(), flat_depth_png(5000));
  write_text((dir.path() / "secret.png").string(), flat_depth_png(5000));
  write_text((tum / "depth.txt").string(), "1.0 depth/1.png\n2.0 ../secret.png\n");
  std::string why = error_of([&] { read_rgbd_sequence(tum.string()); });
  EXPECT_NE(why.find("depth.txt names '../secret.png', outside the sequence's directory"),
            std::string::npos)
      << why;
  write_text((tum / "depth.txt").string(), "1.0 depth/1.png\n1.0 depth/1.png\n");
  why = error_of([&] { read_rgbd_sequence(tum.string()); });
  EXPECT_NE(why.find("depth.txt lists the frame at t = 1.000000 twice"), std::string::npos) << why;

  const fs::path bop = dir.path() / "bop";
  fs::create_directories(bop / "depth");
  write_text((bop / "scene_camera.json").string(),
             R"({"0": {"cam_K": [600, 0.5, 2, 0, 600, 1.5, 0, 0, 1],
                        "cam_R_w2c": [1, 0, 0, 0, 1, 0, 0, 0, 1], "cam_t_w2c": [0, 0, 0]}})");
  write_text((bop / "depth" / "000000.png").string(), flat_depth_png(1000));
  why = error_of([&] { read_rgbd_sequence(bop.string()); });
  EXPECT_NE(why.find("cam_K: not a camera matrix without skew"), std::string::npos) << why;
  // And a translation beyond 10 km, in any layout.
  write_text((bop / "scene_camera.json").string(),
             R"({"0": {"cam_K": [600, 0, 2, 0, 600, 1.5, 0, 0, 1],
                        "cam_R_w2c": [1, 0, 0, 0, 1, 0, 0, 0, 1], "cam_t_w2c": [0, 0, 1e308]}})");
  why = error_of([&] { read_rgbd_sequence(bop.string()); });
  EXPECT_NE(why.find("at most 10000 m"), std::string::npos) << why;
}

// The real sequences: every frame reads, the poses are rigid, and the depth is where the README
// says (0.9-2.9 m for the kitchen, 0.13-1.4 m for the desk).
TEST(RgbdSequence, ViewsOutOfRangeAreRefusedBeforeAFrameIsRead) {
  const ScratchDir dir;
  RgbdDatasetOptions options;
  options.views = 5;
  EXPECT_NE(error_of([&] {
              generate_rgbd_dataset((dir.path() / "no-such-sequence").string(),
                                    (dir.path() / "out").string(), options);
            }).find("views must be 1 to 4"),
            std::string::npos);
  options.views = 2;
  options.view_gap = 7;  // not a multiple of the stride, 5
  EXPECT_NE(error_of([&] {
              generate_rgbd_dataset((dir.path() / "no-such-sequence").string(),
                                    (dir.path() / "out").string(), options);
            }).find("a positive multiple of the frame stride"),
            std::string::npos);
}

// Landmarks of two views on the real kitchen: each kept box also as NAME-v2, fused from its frame
// and the frame 10 later (or earlier), registered from the poses; both searched in the same scenes.
TEST(RgbdSequence, TheRealKitchenGivesLandmarksOfTwoViews) {
  LMK_REQUIRE_SHARED_DATA(data);
  const ScratchDir dir;
  RgbdDatasetOptions options;
  options.frame_stride = 10;
  options.boxes_per_frame = 2;
  options.views = 2;
  options.min_gap = 20;
  const RgbdImport import = generate_rgbd_dataset((data / "real" / "redkitchen").string(),
                                                  (dir.path() / "out").string(), options);
  std::size_t two_views = 0;
  for (const DatasetLandmark& l : import.dataset.landmarks) {
    const Landmark landmark = load_landmark((dir.path() / "out" / l.file).string());
    const bool fused = l.name.size() > 3 && l.name.substr(l.name.size() - 3) == "-v2";
    EXPECT_EQ(landmark.view_count(), fused ? 2u : 1u) << l.name;
    if (!fused) continue;
    ++two_views;
    // The same scenes as the box's landmark of one view, when that one was kept.
    const std::string one = l.name.substr(0, l.name.size() - 3);
    const auto searched_in = [&](const DatasetScene& scene, const std::string& name) {
      return std::any_of(scene.pairs.begin(), scene.pairs.end(),
                         [&](const DatasetPair& p) { return p.landmark == name; });
    };
    const bool one_kept =
        std::any_of(import.dataset.landmarks.begin(), import.dataset.landmarks.end(),
                    [&](const DatasetLandmark& k) { return k.name == one; });
    ASSERT_TRUE(one_kept) << "a box refused in one view is left out in every number of views";
    for (const DatasetScene& scene : import.dataset.scenes) {
      EXPECT_EQ(searched_in(scene, l.name), searched_in(scene, one)) << l.name << " " << scene.name;
    }
  }
  EXPECT_GT(two_views, 0u);
}

// Colour on real frames (issue #35): the desk sequence's colour is registered to its depth, and
// its camera's exposure and white balance drift as it moves. The colour term, whose tolerance was
// chosen on this sequence, keeps every true match in context and turns down look-alikes of other
// colours (docs/evaluation.md, "Colour"): what a change to chroma, the pairing or the defaults must
// not lose.
TEST(RgbdSequence, ColourOnTheRealDeskKeepsEveryTrueMatchAndRemovesFalseOnes) {
  LMK_REQUIRE_SHARED_DATA(data);
  const ScratchDir dir;
  RgbdDatasetOptions options;
  options.read.colour_registered = true;
  const std::string out = (dir.path() / "desk").string();
  const RgbdImport import = generate_rgbd_dataset((data / "real" / "desk").string(), out, options);
  ASSERT_FALSE(import.dataset.landmarks.empty());
  EXPECT_TRUE(load_landmark((dir.path() / "desk" / import.dataset.landmarks[0].file).string())
                  .points.has_colors());
  EvaluationSettings settings;
  settings.in_context_only = true;
  const Counts with = evaluation_row(evaluate(out, import.dataset, settings), "all", 2,
                                     *settings.find.resolved().selection.threshold)
                          .counts;
  settings.find.selection.colour_weight = 0.0;
  const Counts without = evaluation_row(evaluate(out, import.dataset, settings), "all", 2,
                                        *settings.find.resolved().selection.threshold)
                             .counts;
  EXPECT_GT(without.tp, 10u);
  EXPECT_EQ(with.tp, without.tp);
  EXPECT_LT(2 * with.fp, without.fp + 1) << "colour should remove at least half the false matches";
}

TEST(RgbdSequence, ReadsTheRealSequences) {
  LMK_REQUIRE_SHARED_DATA(data);
  for (const auto& [name, lo, hi] :
       {std::tuple<const char*, double, double>{"redkitchen", 0.5, 4.5}, {"desk", 0.1, 2.0}}) {
    const RgbdSequence s = read_rgbd_sequence((data / "real" / name).string());
    EXPECT_EQ(s.layout, "frames") << name;
    EXPECT_EQ(s.frames.size(), 50u) << name;
    const PointCloud cloud = load_rgbd_frame(s.frames.front());
    EXPECT_EQ(cloud.width, 640u);
    EXPECT_EQ(cloud.height, 480u);
    std::vector<float> z;
    for (const auto& p : cloud.points)
      if (is_finite(p)) z.push_back(p.z());
    ASSERT_GT(z.size(), 100000u) << name;
    std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
    EXPECT_GT(z[z.size() / 2], lo) << name;
    EXPECT_LT(z[z.size() / 2], hi) << name;
  }
}

}  // namespace
}  // namespace lmk
