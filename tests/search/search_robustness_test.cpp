// SPDX-License-Identifier: BSD-3-Clause
// The search under bad input (NaN poses, empty or tiny scenes, flat landmarks), under concurrent
// use of one SceneIndex, and the distinctiveness check that capture runs.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>
#include <tuple>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/distinctiveness.h"
#include "lmk/search/find_landmark.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using namespace test_scenes;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class SearchInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new PointCloud(render_scene({kCopies[0]}, true));
    landmark_ = new Landmark(capture(*scene_, box_at(kCopies[0]), "L"));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete landmark_;
  }
  static PointCloud* scene_;
  static Landmark* landmark_;
};
PointCloud* SearchInput::scene_ = nullptr;
Landmark* SearchInput::landmark_ = nullptr;

using test::error_of;

TEST_F(SearchInput, NanPosesAreClearErrors) {
  PointCloud scene = *scene_;
  scene.T_cloud_sensor.translation().x() = kNaN;
  EXPECT_NE(error_of([&] { find_landmark(scene, *landmark_); }).find("sensor pose"),
            std::string::npos);

  Landmark landmark = *landmark_;
  landmark.box.pose.translation().z() = kNaN;
  EXPECT_NE(error_of([&] { find_landmark(*scene_, landmark); }).find("box pose"),
            std::string::npos);

  FindSettings s;
  s.scene.work_volume = Box(pose_from_xyz_rpy({kNaN, 0, 0}, {0, 0, 0}), {1, 1, 1});
  EXPECT_NE(error_of([&] { find_landmark(*scene_, *landmark_, s); }).find("--work-volume"),
            std::string::npos);

  s = FindSettings();
  s.scene.up = Eigen::Vector3d(0, kNaN, 1);
  EXPECT_NE(error_of([&] { find_landmark(*scene_, *landmark_, s); }).find("--up"),
            std::string::npos);
}

TEST_F(SearchInput, EmptyScenesAreClearErrors) {
  EXPECT_NE(error_of([&] { find_landmark(PointCloud(), *landmark_); }).find("no finite point"),
            std::string::npos);
  PointCloud no_returns;  // an organised frame in which the sensor saw nothing
  no_returns.width = 4;
  no_returns.height = 3;
  no_returns.points.assign(12, Eigen::Vector3f::Constant(std::nanf("")));
  EXPECT_NE(error_of([&] { find_landmark(no_returns, *landmark_); }).find("no finite point"),
            std::string::npos);
}

// SceneIndex builds its grids from a whole frame as it is, relying on them to skip the pixels
// without a return: the index of the frame and that of its finite points alone must agree.
TEST_F(SearchInput, AFrameIsIndexedAsItsFinitePointsAre) {
  ASSERT_LT(scene_->count_finite(), scene_->size());  // the rendered frame has empty pixels
  const SceneIndex frame(*scene_);
  const SceneIndex finite(remove_non_finite(*scene_));
  EXPECT_EQ(frame.input_points(), finite.input_points());
  EXPECT_EQ(frame.coarse().points, finite.coarse().points);
  ASSERT_EQ(frame.coarse().normals.size(), finite.coarse().normals.size());
  for (std::size_t k = 0; k < frame.coarse().normals.size(); ++k) {
    const Eigen::Vector3f& a = frame.coarse().normals[k];
    const Eigen::Vector3f& b = finite.coarse().normals[k];
    EXPECT_TRUE(a == b || (!a.allFinite() && !b.allFinite())) << "normal " << k;
  }
  EXPECT_EQ(frame.occupancy().occupied_voxels(), finite.occupancy().occupied_voxels());
  EXPECT_EQ(frame.field().active_voxels(), finite.field().active_voxels());
  EXPECT_EQ(frame.fine().points, finite.fine().points);
}

// A scene smaller than the landmark (a 6 cm patch of the table, then a handful of points) has
// nothing that could be the landmark: the result is empty, with the reason, for both methods.
TEST_F(SearchInput, ScenesSmallerThanTheLandmarkGiveNoMatchAndAReason) {
  const Box patch(pose_from_xyz_rpy({0.2, 0.2, kTable}, {0, 0, 0}), {0.06, 0.06, 0.02});
  const PointCloud small = crop(*scene_, patch);
  ASSERT_GT(small.size(), 20u);
  for (const SearchMethod method : {SearchMethod::fast, SearchMethod::reference}) {
    FindSettings s;
    s.method = method;
    for (std::size_t n : {std::size_t{1}, std::size_t{3}, small.size()}) {
      PointCloud scene = small;
      scene.points.resize(n);
      scene.width = static_cast<std::uint32_t>(n);
      const FindResult r = find_landmark(scene, *landmark_, s);
      EXPECT_TRUE(r.matches.empty()) << setting_name(method) << ", " << n << " points";
      EXPECT_FALSE(describe_rejections(r.stats).empty())
          << setting_name(method) << ", " << n << " points";
    }
  }
}

TEST_F(SearchInput, FlatLandmarksAreRefusedWithTheReason) {
  const Box table_patch(pose_from_xyz_rpy({0.2, 0.2, kTable}, {0, 0, 0.4}), {0.2, 0.15, 0.04});
  const std::string why = error_of([&] { capture(*scene_, table_patch, "patch"); });
  EXPECT_NE(why.find("flat"), std::string::npos) << why;

  // A landmark made flat after capture (as an imported or hand-built one could be) is refused by
  // the search as well.
  Landmark flat = *landmark_;
  for (auto& p : flat.points.points) p.z() = static_cast<float>(kTable);
  EXPECT_NE(error_of([&] { find_landmark(*scene_, flat); }).find("flat"), std::string::npos);

  // A thin straight landmark: a single row of points.
  Landmark straight = *landmark_;
  for (auto& p : straight.points.points) p.y() = p.z() = 0.0f;
  EXPECT_NE(error_of([&] { find_landmark(*scene_, straight); }).find("straight"),
            std::string::npos);

  // The L-shape itself is neither.
  EXPECT_FALSE(degenerate_shape(landmark_->points, 0.005, "L").has_value());
}

// An empty patch of table, captured as a flat landmark on purpose: it matches wherever a patch of
// its size is free, at table height, and never where an object stands in its box.
TEST(FlatPatch, MatchesFreeTableOnlyAndSurvivesTheFile) {
  const PointCloud empty_table = render_scene({}, false);
  const Box patch(pose_from_xyz_rpy({0.0, 0.1, kTable + 0.04}, {0, 0, 0}), {0.16, 0.16, 0.1});
  CaptureSettings settings;
  settings.allow_flat = true;
  const Landmark landmark = capture(empty_table, patch, "patch", settings);
  const test::ScratchDir dir;
  save_landmark(dir.file("patch.lmk"), landmark);
  const Landmark loaded = load_landmark(dir.file("patch.lmk"));
  EXPECT_TRUE(loaded.settings.allow_flat);

  const PointCloud scene = render_scene(kCopies, true);
  const FindResult result = find_landmark(scene, loaded);
  ASSERT_FALSE(result.matches.empty()) << describe_rejections(result.stats);
  for (const Match& m : result.matches) {
    EXPECT_NEAR(m.box.center().z(), patch.center().z(), 0.01);
    EXPECT_GT(m.box.pose.linear().col(2).z(), std::cos(5.0 * M_PI / 180.0));  // level
    // No L-shape's post (its lower part, 2 cm above the table) inside the patch's box.
    for (const Eigen::Vector2d& copy : kCopies) {
      EXPECT_FALSE(m.box.contains(Eigen::Vector3d(copy.x(), copy.y(), kTable + 0.02)))
          << "a patch on the L at " << copy.transpose();
    }
  }
}

// Several threads search one SceneIndex at once, each with its own landmark view: every result is
// the one a lone search gives.
TEST(SceneIndexSharing, ConcurrentSearchesGiveTheSerialResult) {
  const PointCloud scene = render_scene(kCopies, true);
  const Landmark landmark = capture(scene, box_at(kCopies[0]), "L");
  FindSettings s;
  s.execution.threads = 1;
  const SceneIndex index(scene, s.scene);
  const FindResult serial = find_landmark(index, landmark, s);
  ASSERT_EQ(serial.matches.size(), kCopies.size());

  constexpr int kThreads = 4, kRepeats = 3;
  std::vector<std::vector<FindResult>> results(kThreads);
  std::vector<std::thread> workers;
  for (int t = 0; t < kThreads; ++t) {
    workers.emplace_back([&, t] {
      for (int k = 0; k < kRepeats; ++k) results[t].push_back(find_landmark(index, landmark, s));
    });
  }
  for (std::thread& w : workers) w.join();
  for (const auto& per_thread : results) {
    for (const FindResult& r : per_thread) {
      ASSERT_EQ(r.matches.size(), serial.matches.size());
      for (std::size_t i = 0; i < r.matches.size(); ++i) {
        EXPECT_EQ(r.matches[i].error, serial.matches[i].error);
        EXPECT_TRUE(r.matches[i].box.pose.isApprox(serial.matches[i].box.pose, 0.0));
      }
    }
  }
}

// A tracker indexes one frame around each of its landmarks: the indexes share the frame's range
// image (SceneIndexReuse::image), built once, and search as they would with an image of their own.
TEST(SceneIndexSharing, IndexesOfOneFrameShareItsImageAndSearchAsWithTheirOwn) {
  const PointCloud scene = render_scene(kCopies, true);
  const Landmark landmark = capture(scene, box_at(kCopies[0]), "L");
  FindSettings s;
  const SceneIndex first(scene, s.scene);
  const FrameImage image = first.shared_range_image();
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(image.get(), first.range_image());

  // The image is the frame's whatever the index: another index builds the same one.
  const SceneIndex own(scene, s.scene);
  ASSERT_NE(own.range_image(), nullptr);
  const PinholeIntrinsics& a = own.range_image()->intrinsics();
  const PinholeIntrinsics& b = image->intrinsics();
  EXPECT_EQ(std::tie(a.fx, a.fy, a.cx, a.cy, a.width, a.height),
            std::tie(b.fx, b.fy, b.cx, b.cy, b.width, b.height));
  const std::vector<float>& mine = own.range_image()->depths();
  const std::vector<float>& shared = image->depths();
  ASSERT_EQ(mine.size(), shared.size());
  for (std::size_t i = 0; i < mine.size(); ++i) {
    if (std::isnan(mine[i])) {
      EXPECT_TRUE(std::isnan(shared[i])) << "pixel " << i;
    } else {
      EXPECT_EQ(mine[i], shared[i]) << "pixel " << i;
    }
  }

  // An index around one copy only, with the frame's image and with its own.
  FindSettings around = s;
  Box volume = box_at(kCopies[0]);
  volume.size += Eigen::Vector3d::Constant(0.2);
  around.scene.work_volume = volume;
  SceneIndexReuse reuse;
  reuse.image = image;
  const SceneIndex with_shared(scene, around.scene, {}, reuse);
  EXPECT_EQ(with_shared.range_image(), image.get());  // the very image, not a copy
  const SceneIndex with_own(scene, around.scene);
  const FindResult r1 = find_landmark(with_shared, landmark, around);
  const FindResult r2 = find_landmark(with_own, landmark, around);
  ASSERT_EQ(r1.matches.size(), 1u) << describe_rejections(r1.stats);
  ASSERT_EQ(r2.matches.size(), 1u);
  EXPECT_EQ(r1.matches[0].error, r2.matches[0].error);
  EXPECT_EQ(r1.matches[0].confidence.probability, r2.matches[0].confidence.probability);
  EXPECT_TRUE(r1.matches[0].box.pose.isApprox(r2.matches[0].box.pose, 0.0));

  // An image shared as absent (the frame was no view from its sensor pose) is not built again.
  reuse.image = FrameImage();
  EXPECT_EQ(SceneIndex(scene, around.scene, {}, reuse).range_image(), nullptr);
}

TEST(Distinctiveness, NamesEveryOtherCopyInTheCaptureScene) {
  const PointCloud scene = render_scene(kCopies, true);
  const DistinctivenessReport report =
      check_distinctiveness(scene, capture(scene, box_at(kCopies[0]), "L"));
  EXPECT_TRUE(report.found_itself);
  ASSERT_EQ(report.other_instances.size(), kCopies.size() - 1);
  for (const Match& m : report.other_instances) {
    const double to_second = (m.box.center() - box_at(kCopies[1]).center()).norm();
    const double to_third = (m.box.center() - box_at(kCopies[2]).center()).norm();
    EXPECT_LT(std::min(to_second, to_third), 0.01);
  }
}

TEST(Distinctiveness, ALoneLandmarkAmongDistractorsIsDistinctive) {
  const PointCloud scene = render_scene({kCopies[1]}, true);
  const DistinctivenessReport report =
      check_distinctiveness(scene, capture(scene, box_at(kCopies[1]), "L"));
  EXPECT_TRUE(report.found_itself);
  EXPECT_TRUE(report.other_instances.empty());
}

// The check searches the capture scene prepared as the capture prepared it: a landmark captured
// with depth smoothing is checked in the smoothed scene, as its searches would smooth theirs, not
// in the raw one. The camera stands 1.2 m further back than the tests' own, so that the table lies
// beyond 1.8 m, where smoothing applies.
TEST(Distinctiveness, SearchesTheCaptureSceneAsTheCapturePreparedIt) {
  const Eigen::Isometry3d far_camera = capture_camera() * Eigen::Translation3d(0.0, 0.0, -1.2);
  const PointCloud scene = render_scene({kCopies[1]}, true, {}, far_camera);
  CaptureSettings smoothed_capture;
  smoothed_capture.depth_smoothing = 2;
  const Landmark landmark = capture(scene, box_at(kCopies[1]), "L", smoothed_capture);
  const DistinctivenessReport report = check_distinctiveness(scene, landmark);
  FindSettings smoothed_search;
  smoothed_search.scene.depth_smoothing = 2;
  const FindResult expected = find_landmark(scene, landmark, smoothed_search);
  const FindResult raw = find_landmark(scene, landmark);
  ASSERT_EQ(report.search.matches.size(), expected.matches.size());
  ASSERT_FALSE(expected.matches.empty());
  for (std::size_t i = 0; i < expected.matches.size(); ++i) {
    EXPECT_EQ(report.search.matches[i].error, expected.matches[i].error);
  }
  ASSERT_FALSE(raw.matches.empty());
  EXPECT_NE(raw.matches.front().error, expected.matches.front().error);
}

}  // namespace
}  // namespace lmk
