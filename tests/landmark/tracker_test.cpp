// SPDX-License-Identifier: BSD-3-Clause
// The tracker (issue #48) on a rendered sequence: an L-shape pushed 1 cm per frame is followed
// frame by frame, taken away it is lost, put back elsewhere it is found again.
#include "lmk/landmark/tracker.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "tests/landmark/l_shape_scene.h"

namespace lmk {
namespace {

using namespace test_scenes;

TEST(Tracker, FollowsAPushedLandmarkLosesItWhenTakenAndFindsItAgain) {
  const Eigen::Vector2d start = kCopies[0];
  const auto landmark =
      std::make_shared<const Landmark>(capture(render_scene({start}, true), box_at(start), "L"));
  Tracker tracker({landmark});
  const auto expect_at = [](const TrackedLandmark& t, const Eigen::Vector2d& xy, int frame) {
    ASSERT_TRUE(t.match) << "frame " << frame << ": " << to_string(t.state) << ", "
                         << t.lost_because;
    EXPECT_LT((t.match->box.center() - box_at(xy).center()).norm(), 0.005) << "frame " << frame;
  };

  double followed_seconds = 0.0, searched_seconds = 0.0;
  for (int k = 0; k <= 5; ++k) {
    const Eigen::Vector2d xy = start + Eigen::Vector2d(0.01 * k, 0.005 * k);
    const std::vector<TrackedLandmark> now = tracker.update(render_scene({xy}, true));
    ASSERT_EQ(now.size(), 1u);
    EXPECT_EQ(now[0].state, k == 0 ? TrackState::found : TrackState::tracking)
        << "frame " << k << ": " << to_string(now[0].state) << " " << now[0].lost_because;
    expect_at(now[0], xy, k);
    (k == 0 ? searched_seconds : followed_seconds) += now[0].seconds;
  }
  std::printf("searched in %.1f ms, followed in %.1f ms per frame\n", 1e3 * searched_seconds,
              1e3 * followed_seconds / 5);

  // Taken away: lost, with why.
  const std::vector<TrackedLandmark> gone = tracker.update(render_scene({}, true));
  EXPECT_EQ(gone[0].state, TrackState::lost);
  EXPECT_FALSE(gone[0].match);
  EXPECT_FALSE(gone[0].lost_because.empty());

  // Put back 20 cm away: found again there, then followed.
  const Eigen::Vector2d back = start + Eigen::Vector2d(0.2, 0.0);
  std::vector<TrackedLandmark> again = tracker.update(render_scene({back}, true));
  EXPECT_EQ(again[0].state, TrackState::found_again) << to_string(again[0].state);
  expect_at(again[0], back, 7);
  again = tracker.update(render_scene({back}, true));
  EXPECT_EQ(again[0].state, TrackState::tracking) << to_string(again[0].state);
  expect_at(again[0], back, 8);
}

}  // namespace
}  // namespace lmk
