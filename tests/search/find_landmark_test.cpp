// SPDX-License-Identifier: BSD-3-Clause
// FindLandmark, both methods, on synthetic scenes built here and on the real milk scene; and the
// fast method on rotated and tilted landmarks, where the paper failed.

#include "lmk/search/find_landmark.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "lmk/datasets/real_data.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/search/fast/fast_landmark.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
// Test names and messages show the method by name.
void PrintTo(SearchMethod method, std::ostream* out) { *out << setting_name(method); }

namespace {

using namespace test_scenes;

class Search : public ::testing::TestWithParam<SearchMethod> {
 protected:
  static void SetUpTestSuite() {
    scene_ = new PointCloud(render_scene(kCopies, true));
    landmark_ = new Landmark(capture(*scene_, box_at(kCopies[0]), "L"));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete landmark_;
  }
  static FindSettings settings() {
    FindSettings s;
    s.method = GetParam();
    return s;
  }
  static PointCloud* scene_;
  static Landmark* landmark_;
};
PointCloud* Search::scene_ = nullptr;
Landmark* Search::landmark_ = nullptr;

TEST_P(Search, FindsEveryCopyOnceAndNothingElse) {
  const FindResult r = find_landmark(*scene_, *landmark_, settings());
  ASSERT_EQ(r.matches.size(), kCopies.size());
  std::vector<int> found(kCopies.size(), 0);
  for (const Match& m : r.matches) {
    for (std::size_t c = 0; c < kCopies.size(); ++c) {
      if ((m.box.center() - box_at(kCopies[c]).center()).norm() < 0.01) ++found[c];
    }
    EXPECT_LT(m.error, r.stats.threshold);
    // The evaluation protocol's rotation tolerance for a true positive: 15 degrees.
    EXPECT_LT(rotation_angle_between(m.box.pose.linear(), Eigen::Matrix3d::Identity()), 0.2618);
  }
  EXPECT_EQ(found, std::vector<int>(kCopies.size(), 1));
  EXPECT_TRUE(std::is_sorted(r.matches.begin(), r.matches.end(),
                             [](const Match& a, const Match& b) { return a.error < b.error; }));
  if (GetParam() == SearchMethod::reference) {
    EXPECT_EQ(r.stats.seeds,
              std::min<std::size_t>(1000, (r.stats.scene_points_used * 5 + 99) / 100));
  } else {  // about 12 seeds per instance: a few dozen for the three copies here, not hundreds
    EXPECT_GE(r.stats.seeds, 3 * 12u);
    EXPECT_LE(r.stats.seeds, 1000u);
  }
  EXPECT_EQ(r.stats.metric, GetParam() == SearchMethod::fast ? "visibility" : "paper");
  EXPECT_GT(r.stats.icp_iterations, 0u);
}

TEST_P(Search, FindsNothingInASceneWithoutTheShape) {
  const FindResult r = find_landmark(render_scene({}, true), *landmark_, settings());
  EXPECT_TRUE(r.matches.empty()) << "best error " << r.matches.front().error;
  EXPECT_GT(r.stats.after_nms, 0u);  // candidates existed, the threshold refused them
}

TEST_P(Search, SameResultWhateverTheThreadCount) {
  FindSettings one = settings(), two = settings();
  one.execution.threads = 1;
  two.execution.threads = 2;
  one.sampling.max_seeds = two.sampling.max_seeds = 150;
  const FindResult a = find_landmark(*scene_, *landmark_, one);
  const FindResult b = find_landmark(*scene_, *landmark_, two);
  ASSERT_EQ(a.matches.size(), b.matches.size());
  for (std::size_t i = 0; i < a.matches.size(); ++i) {
    EXPECT_EQ(a.matches[i].seed_index, b.matches[i].seed_index);
    EXPECT_EQ(a.matches[i].error, b.matches[i].error);
    EXPECT_TRUE(a.matches[i].box.pose.isApprox(b.matches[i].box.pose, 0.0));
  }
  EXPECT_EQ(a.stats.icp_iterations, b.stats.icp_iterations);
}

TEST_P(Search, WorkVolumeAndAlignedPoints) {
  FindSettings s = settings();
  s.scene.work_volume =
      Box(pose_from_xyz_rpy({kCopies[1].x() + 0.05, kCopies[1].y(), kTable + 0.05}, {0, 0, 0}),
          {0.4, 0.3, 0.3});
  s.execution.keep_aligned_points = true;
  const FindResult r = find_landmark(*scene_, *landmark_, s);
  ASSERT_EQ(r.matches.size(), 1u);
  EXPECT_LT((r.matches[0].box.center() - box_at(kCopies[1]).center()).norm(), 0.01);
  EXPECT_EQ(r.matches[0].aligned_points.size(), landmark_->points.size());
  EXPECT_LT(r.stats.scene_points_used, voxel_downsample(*scene_, 0.005).size());
}

TEST_P(Search, BadSettingsAreErrors) {
  FindSettings s = settings();
  s.method = static_cast<SearchMethod>(7);  // a value without a name
  EXPECT_THROW(find_landmark(*scene_, *landmark_, s), Error);
  s = FindSettings();
  s.selection.metric = "nope";
  EXPECT_THROW(find_landmark(*scene_, *landmark_, s), Error);
  s = FindSettings();
  s.scene.work_volume = Box(pose_from_xyz_rpy({9, 9, 9}, {0, 0, 0}), {0.1, 0.1, 0.1});
  EXPECT_THROW(find_landmark(*scene_, *landmark_, s), Error);
  s = FindSettings();
  s.selection.threshold = -1;
  EXPECT_THROW(find_landmark(*scene_, *landmark_, s), Error);
  EXPECT_THROW(find_landmark(PointCloud(), *landmark_), Error);
}

TEST_P(Search, ALandmarkIndexBuiltOnceGivesEverySearchItsOwnResult) {
  FindSettings s = settings();
  s.sampling.max_seeds =
      s.method == SearchMethod::fast ? 150 : 8;  // the reference's seeds are slow
  const LandmarkIndex prepared(*landmark_, s);
  const SceneIndex scene(*scene_, s.scene);
  // Two searches with one index (and in another scene between them) equal fresh ones.
  for (int round = 0; round < 2; ++round) {
    const FindResult fresh = find_landmark(*scene_, *landmark_, s);
    const FindResult shared = find_landmark(scene, prepared, s);
    ASSERT_EQ(shared.matches.size(), fresh.matches.size());
    for (std::size_t i = 0; i < fresh.matches.size(); ++i) {
      EXPECT_EQ(shared.matches[i].error, fresh.matches[i].error);
      EXPECT_TRUE(shared.matches[i].box.pose.isApprox(fresh.matches[i].box.pose, 0.0));
    }
    EXPECT_EQ(shared.stats.seeds, fresh.stats.seeds);
    const PointCloud empty_table = render_scene({}, true);
    EXPECT_TRUE(find_landmark(SceneIndex(empty_table, s.scene), prepared, s).matches.empty());
  }
}

TEST_P(Search, ALandmarkIndexRefusesSearchesItWasNotBuiltFor) {
  const FindSettings s = settings();
  const LandmarkIndex prepared(*landmark_, s);
  const SceneIndex scene(*scene_, s.scene);
  FindSettings other = s;
  other.method = s.method == SearchMethod::fast ? SearchMethod::reference : SearchMethod::fast;
  std::string why;
  EXPECT_FALSE(prepared.suits(other, &why));
  EXPECT_NE(why.find("built for method " + setting_name(s.method)), std::string::npos) << why;
  EXPECT_THROW(find_landmark(scene, prepared, other), Error);
  if (s.method == SearchMethod::fast) {
    other = s;
    other.fast.vote_leaf_fraction *= 2.0;
    EXPECT_FALSE(prepared.suits(other));
    other = s;
    other.scene.coarse_leaf *= 2.0;
    EXPECT_FALSE(prepared.suits(other));
    other = s;
    other.selection.threshold = 0.002;  // selection and seeds do not matter to the landmark
    other.sampling.max_seeds = 10;
    EXPECT_TRUE(prepared.suits(other));
  } else {
    // The reference derives nothing from the landmark: no setting but the method unsuits it.
    EXPECT_EQ(dynamic_cast<const detail::FastLandmark*>(&prepared.method_landmark()), nullptr);
    other = s;
    other.scene.coarse_leaf *= 2.0;
    EXPECT_TRUE(prepared.suits(other));
  }
}

// Issue #62: each method aligns at a given pose as it aligns its own candidates, so that
// score_pose (lmk eval --explain) and find_near_pose (the tracker) work with either: from a pose
// 1 cm off an instance, both end on it.
TEST_P(Search, EachMethodAlignsAtAGivenPoseAsItAlignsItsOwn) {
  const FindSettings s = settings();
  const LandmarkIndex prepared(*landmark_, s);
  const SceneIndex scene(*scene_, s.scene);
  const Box truth = box_at(kCopies[1]);
  Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  near.translation() = truth.center() - landmark_->box.center() + Eigen::Vector3d(0.01, 0, 0);
  const Match scored = score_pose(scene, prepared, s, near);
  EXPECT_LT((scored.box.center() - truth.center()).norm(), 0.005);
  EXPECT_LT(scored.error, *s.resolved().selection.threshold);
  const FindResult followed = find_near_pose(scene, prepared, s, near);
  ASSERT_EQ(followed.matches.size(), 1u) << describe_rejections(followed.stats);
  EXPECT_LT((followed.matches[0].box.center() - truth.center()).norm(), 0.005);
  EXPECT_EQ(followed.stats.method, s.method);
}

INSTANTIATE_TEST_SUITE_P(Methods, Search,
                         ::testing::Values(SearchMethod::fast, SearchMethod::reference),
                         [](const auto& info) { return setting_name(info.param); });

// The issues' acceptance for one trial: does a match lie within 1 cm and 5 degrees of `truth`?
// Returns 1 if so; otherwise says which trial missed, and returns 0.
int count_trial(const FindResult& r, const Box& truth, int trial, double yaw, double tilt) {
  for (const Match& m : r.matches) {
    if ((m.box.center() - truth.center()).norm() < 0.01 &&
        rotation_angle_between(m.box.pose.linear(), truth.pose.linear()) < 5.0 * M_PI / 180) {
      return 1;
    }
  }
  std::printf("trial %d missed: yaw %.0f tilt %.0f deg, %zu matches\n", trial, yaw * 180 / M_PI,
              tilt * 180 / M_PI, r.matches.size());
  return 0;
}

// Issue acceptance: the L-shape at a random yaw in [0, 360) degrees and a tilt of up to 45 degrees
// (about gravity, +z of the scenes' base frame), floating above the table among the distractors;
// the fast method must find it within 1 cm and 5 degrees in at least 95 of 100 seeded trials.
// The camera turns with the landmark, so that the faces captured are the faces seen: a landmark
// is a partial view, and a turn that hides every captured face leaves nothing to match. The table
// and the clutter stay where they were, so the background changes around the landmark.
TEST(FastSearchRotation, FindsRotatedAndTiltedLandmarks) {
  const PointCloud capture_scene = render_scene(kCopies, true);
  const Box box = box_at(kCopies[0]);
  CaptureSettings in_base_frame;
  in_base_frame.base_frame = true;
  const Landmark landmark = capture(capture_scene, box, "L", in_base_frame);
  FindSettings settings;
  settings.scene.base_frame = true;
  SplitMix64 rng(2026);
  int found = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const double yaw = 2.0 * M_PI * rng.uniform01();
    const double tilt = 0.25 * M_PI * rng.uniform01();
    const double azimuth = 2.0 * M_PI * rng.uniform01();
    const Eigen::Vector3d tilt_axis(std::cos(azimuth), std::sin(azimuth), 0.0);
    // The capture pose of the L-shape's origin, moved to a new place 15 cm above the table and
    // turned about its own origin.
    const Eigen::Isometry3d T_world_l0 =
        pose_from_xyz_rpy({kCopies[0].x(), kCopies[0].y(), kTable}, {0, 0, 0});
    Eigen::Isometry3d T_world_l = Eigen::Isometry3d::Identity();
    T_world_l.linear() =
        (Eigen::AngleAxisd(tilt, tilt_axis) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
    T_world_l.translation() = Eigen::Vector3d(0.1 * rng.uniform01(), 0.05, kTable + 0.15);
    const Eigen::Isometry3d T_scene_capture = T_world_l * T_world_l0.inverse();
    const Box truth = box.transformed(T_scene_capture);
    const PointCloud scene =
        render_scene({}, true, {T_world_l}, T_scene_capture * capture_camera());
    const FindResult r = find_landmark(scene, landmark, settings);
    found += count_trial(r, truth, trial, yaw, tilt);
  }
  std::printf("fast found %d of 100 rotated and tilted landmarks\n", found);
  EXPECT_GE(found, 95);
}

// An upright search reports no pose beyond its tilt limit, even where alignment could slide a
// candidate there. An L-shape tipped by 45 degrees floats above the table, seen by a camera tipped
// with it (as in the test above): within a limit of 60 degrees it is found, and at a limit of 30
// degrees nothing tipped further comes back, it included.
TEST(FastSearchRotation, AnUprightSearchReportsNoPoseBeyondItsTiltLimit) {
  const PointCloud capture_scene = render_scene(kCopies, true);
  CaptureSettings in_base_frame;
  in_base_frame.base_frame = true;
  const Landmark landmark = capture(capture_scene, box_at(kCopies[0]), "L", in_base_frame);
  const Eigen::Isometry3d T_world_l0 =
      pose_from_xyz_rpy({kCopies[0].x(), kCopies[0].y(), kTable}, {0, 0, 0});
  const Eigen::Isometry3d T_world_tipped =
      pose_from_xyz_rpy({0.05, 0.05, kTable + 0.15}, {M_PI / 4.0, 0.0, 0.3});
  const Eigen::Isometry3d T_scene_capture = T_world_tipped * T_world_l0.inverse();
  const Box tipped = box_at(kCopies[0]).transformed(T_scene_capture);
  const PointCloud scene =
      render_scene({}, true, {T_world_tipped}, T_scene_capture * capture_camera());
  FindSettings settings;
  settings.scene.base_frame = true;
  const auto found_tipped = [&](const FindResult& r) {
    return std::any_of(r.matches.begin(), r.matches.end(), [&](const Match& m) {
      return (m.box.center() - tipped.center()).norm() < 0.01;
    });
  };
  EXPECT_TRUE(found_tipped(find_landmark(scene, landmark, settings)));
  settings.fast.max_tilt = M_PI / 6.0;
  const FindResult limited = find_landmark(scene, landmark, settings);
  EXPECT_FALSE(found_tipped(limited));
  for (const Match& m : limited.matches) {
    const double cos_tilt =
        (m.T_scene_capture.linear() * landmark.up).dot(Eigen::Vector3d::UnitZ());
    EXPECT_GE(cos_tilt, std::cos(settings.fast.max_tilt) - 1e-9);
  }
}

// Issue acceptance, real data: the milk carton captured in its Kinect frame is searched in 50
// copies of that frame, each picked up and put down by a random rigid motion (any yaw about the
// camera's up axis, a tilt of up to 30 degrees about a random horizontal axis, a translation of up
// to 0.5 m), sensor included. Fast must find it within 1 cm and 5 degrees in at least 48.
TEST(RealData, FastFindsTheMilkCartonInTransformedCopiesOfItsFrame) {
  LMK_REQUIRE_SHARED_DATA(data);
  const MilkWorkload milk = load_milk_workload(data);
  // In place first: the capture itself must come back at the identity.
  const FindResult in_place = find_landmark(milk.scene, milk.landmark);
  ASSERT_FALSE(in_place.matches.empty());
  EXPECT_LT((in_place.matches.front().box.center() - milk.box.center()).norm(), 0.005);

  const Eigen::Vector3d camera_up = -Eigen::Vector3d::UnitY();  // the frame is the camera's
  SplitMix64 rng(48);
  int found = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const double yaw = 2.0 * M_PI * rng.uniform01();
    const double tilt = M_PI / 6.0 * rng.uniform01();
    const double azimuth = 2.0 * M_PI * rng.uniform01();
    const Eigen::Vector3d tilt_axis(std::cos(azimuth), 0.0, std::sin(azimuth));  // horizontal
    Eigen::Vector3d shift;
    do {
      shift = Eigen::Vector3d(rng.uniform01(), rng.uniform01(), rng.uniform01()) * 1.0 -
              Eigen::Vector3d::Constant(0.5);
    } while (shift.norm() > 0.5);
    // Turned about the carton, so that the translation is the carton's own.
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        (Eigen::AngleAxisd(tilt, tilt_axis) * Eigen::AngleAxisd(yaw, camera_up)).toRotationMatrix();
    T.translation() = milk.box.center() - T.linear() * milk.box.center() + shift;
    const Box truth = milk.box.transformed(T);
    const FindResult r = find_landmark(milk.scene.transformed(T), milk.landmark);
    found += count_trial(r, truth, trial, yaw, tilt);
  }
  std::printf("fast found the milk carton in %d of 50 transformed frames\n", found);
  EXPECT_GE(found, 48);
}

// The same landmark in another static scene: the three grabber frames hold no milk carton. Reports
// what the search returns; the frames must be searched without error.
TEST(RealData, MilkCartonInTheGrabberFrames) {
  LMK_REQUIRE_SHARED_DATA(data);
  const MilkWorkload milk = load_milk_workload(data);
  std::vector<std::filesystem::path> frames;
  for (const auto& entry : std::filesystem::directory_iterator(data / "pcl")) {
    if (entry.path().filename().string().rfind("grabber_frame_", 0) == 0) {
      frames.push_back(entry.path());
    }
  }
  std::sort(frames.begin(), frames.end());
  ASSERT_EQ(frames.size(), 3u);
  for (const auto& frame : frames) {
    const std::string name = frame.filename().string();
    const FindResult r = find_landmark(read_cloud(frame.string()), milk.landmark);
    std::printf("%s: %zu match%s (%s)\n", name.c_str(), r.matches.size(),
                r.matches.size() == 1 ? "" : "es", describe_rejections(r.stats).c_str());
    for (const Match& m : r.matches) {
      const Eigen::Vector3d c = m.box.center();
      std::printf("  at %.3f %.3f %.3f, error %.2f mm, coverage %.2f, empty %zu/%zu\n", c.x(),
                  c.y(), c.z(), 1000 * m.error, m.terms.coverage(), m.terms.empty_space->violations,
                  m.terms.empty_space->probes);
    }
  }
}

}  // namespace
}  // namespace lmk
