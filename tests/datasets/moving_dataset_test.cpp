// SPDX-License-Identifier: BSD-3-Clause
// The moving preset's sequences (issue #48): an object pushed 0.5-3 cm a frame, carried once 20-40
// cm away, the ground truth of every frame; and the tracker scored on them, as lmk eval-track does.

#include "lmk/datasets/moving_dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "lmk/datasets/track_sequences.h"
#include "lmk/eval/track_evaluation.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// Where the object is in each frame of the sequence: its box centre, or nothing while carried.
std::vector<std::optional<Eigen::Vector3d>> centres(const Dataset& d, const TrackSequence& s) {
  std::vector<std::optional<Eigen::Vector3d>> out;
  for (const std::string& name : s.frames) {
    for (const DatasetScene& scene : d.scenes) {
      if (scene.name != name) continue;
      const DatasetPair pair = d.pair(scene, s.landmark);
      out.push_back(pair.instances.empty()
                        ? std::nullopt
                        : std::optional<Eigen::Vector3d>(pair.instances[0].translation()));
    }
  }
  return out;
}

// Generated once for the tests below, and under CTest once for the run (test::shared_run_data):
// two detergent-bottle sequences of 24 frames, the first with a still camera and the second
// panning. The tests only read it.
class MovingBottle : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(
        test::shared_run_data("moving-bottle", [](const std::filesystem::path& dir) {
          MovingOptions options;
          options.landmarks = {"tide_bottle"};
          options.frames = 24;
          generate_moving_dataset(dir.string(), options);
        }));
    dataset_ = new Dataset(load_dataset(dir_->string()));
  }
  static void TearDownTestSuite() {
    delete dataset_;
    delete dir_;
  }
  static std::string dir() { return dir_->string(); }
  static std::filesystem::path* dir_;
  static Dataset* dataset_;
};
std::filesystem::path* MovingBottle::dir_ = nullptr;
Dataset* MovingBottle::dataset_ = nullptr;

TEST_F(MovingBottle, PushesTheObjectAFewCentimetresAFrameAndCarriesItOnce) {
  const std::vector<TrackSequence> sequences = load_track_sequences(dir(), *dataset_);
  ASSERT_EQ(sequences.size(), 2u);
  for (const TrackSequence& s : sequences) {
    ASSERT_EQ(s.frames.size(), 24u);
    ASSERT_TRUE(s.carry);
    const auto where = centres(*dataset_, s);
    ASSERT_EQ(where.size(), 24u);
    for (std::size_t f = 0; f < where.size(); ++f) {
      const bool carried = f >= s.carry->from && f < s.carry->back;
      EXPECT_EQ(where[f].has_value(), !carried) << s.name << " frame " << f;
      if (f == 0 || carried || f == s.carry->back) continue;
      const double step = (*where[f] - *where[f - 1]).norm();
      EXPECT_GE(step, 0.0049) << s.name << " frame " << f;
      EXPECT_LE(step, 0.0301) << s.name << " frame " << f;
    }
    const double carried = (*where[s.carry->back] - *where[s.carry->from - 1]).norm();
    EXPECT_GE(carried, 0.2) << s.name;
    EXPECT_LE(carried, 0.4) << s.name;
  }
  // The first sequence's camera stands still, the second's pans.
  const auto camera = [&](const TrackSequence& s, std::size_t f) {
    for (const DatasetScene& scene : dataset_->scenes)
      if (scene.name == s.frames[f]) return scene.T_scene_sensor;
    return Eigen::Isometry3d::Identity();
  };
  EXPECT_TRUE(camera(sequences[0], 0).isApprox(camera(sequences[0], 23)));
  const double turned = Eigen::AngleAxisd(camera(sequences[1], 0).linear().transpose() *
                                          camera(sequences[1], 23).linear())
                            .angle();
  EXPECT_NEAR(turned * 180.0 / M_PI, 23 * 0.15, 0.01);
  // Each frame is the organised frame of a Kinect.
  const PointCloud frame = read_cloud((*dir_ / dataset_->scenes[0].file).string());
  EXPECT_EQ(frame.width, 640u);
  EXPECT_EQ(frame.height, 480u);
}

TEST_F(MovingBottle, TheTrackerNoticesTheCarryAndFindsTheBottleAgainWhereItWasPutDown) {
  TrackEvaluationOptions options;
  options.track.find.execution.threads = 2;
  const TrackEvaluation e = evaluate_tracking(dir(), options);
  ASSERT_EQ(e.sequences.size(), 2u);
  for (const SequenceResult& s : e.sequences) {
    ASSERT_TRUE(s.carry_noticed_after) << s.name;
    EXPECT_LE(*s.carry_noticed_after, 1u) << s.name;
    ASSERT_TRUE(s.refound_after) << s.name;
    EXPECT_LE(*s.refound_after, 4u) << s.name;
    EXPECT_EQ(s.pose_while_away, 0u) << s.name;  // never a pose where nothing is
    EXPECT_EQ(s.lost_in_view, 0u) << s.name;
    // The frames it follows are followed, not searched: a state per frame, the first found.
    EXPECT_EQ(s.frames.front().state, TrackState::found);
    EXPECT_EQ(s.frames[s.carry->back].state, TrackState::found_again);
  }
  EXPECT_GE(static_cast<double>(e.within()), 0.9 * static_cast<double>(e.in_view()));
  // The report and its JSON say the same.
  EXPECT_NE(
      tracking_report(e).find(std::to_string(e.within()) + " of " + std::to_string(e.in_view())),
      std::string::npos);
  EXPECT_NE(tracking_json(e).find("\"carry_noticed_after\""), std::string::npos);
}

TEST_F(MovingBottle, SequencesThatNameWhatTheDatasetDoesNotHoldAreRefused) {
  // This test rewrites the sequences: on a copy of its own, apart from the other tests'.
  const test::ScratchDir own;
  std::filesystem::copy(dir(), own.path(), std::filesystem::copy_options::recursive);
  const std::string copy = own.path().string();
  std::vector<TrackSequence> sequences = load_track_sequences(copy, *dataset_);
  // A real sequence's pose check (lmk gen --from-rgbd) is written and read back.
  sequences[1].pose_check = PoseCheck{0.011, 0.009};
  save_track_sequences(copy, *dataset_, sequences);
  const std::vector<TrackSequence> back = load_track_sequences(copy, *dataset_);
  ASSERT_TRUE(back[1].pose_check);
  EXPECT_DOUBLE_EQ(back[1].pose_check->translation, 0.011);
  EXPECT_DOUBLE_EQ(back[1].pose_check->rotation, 0.009);
  EXPECT_FALSE(back[0].pose_check);
  EXPECT_EQ(back[0].carry->from, sequences[0].carry->from);
  TrackSequence bad = sequences[0];
  bad.name = "other";
  bad.frames.push_back("no-such-scene");
  EXPECT_THROW(save_track_sequences(copy, *dataset_, {bad}), Error);
  bad = sequences[0];
  bad.name = "other";
  bad.carry = Carry{5, 5};
  EXPECT_THROW(save_track_sequences(copy, *dataset_, {bad}), Error);
  // Issue #61, finding 9: the sequences and their frames are counted before they are read.
  const std::string file = (own.path() / "sequences.json").string();
  nlohmann::json j = nlohmann::json::parse(test::read_bytes(file));
  const nlohmann::json one = j["sequences"][0];
  j["sequences"] = nlohmann::json::array();
  for (std::size_t i = 0; i <= kMaxTrackSequences; ++i) j["sequences"].push_back(one);
  test::write_text(file, j.dump());
  const auto error_of = [&] {
    try {
      load_track_sequences(copy, *dataset_);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  EXPECT_NE(error_of().find("lists 1001 sequences; at most 1000"), std::string::npos);
  j["sequences"] = nlohmann::json::array({one});
  j["sequences"][0]["frames"] = std::vector<std::string>(kMaxTrackFrames + 1, "x");
  test::write_text(file, j.dump());
  EXPECT_NE(error_of().find("lists 10001 frames; at most 10000"), std::string::npos);
  MovingOptions options;
  options.frames = 5;
  EXPECT_THROW(generate_moving_dataset(copy, options), Error);
  options.frames = 20;
  options.landmarks = {"chair_corner"};
  EXPECT_THROW(generate_moving_dataset(copy, options), Error);
}

}  // namespace
}  // namespace lmk
