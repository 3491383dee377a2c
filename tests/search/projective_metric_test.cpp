// SPDX-License-Identifier: BSD-3-Clause
// The projective visibility metric, worked out by hand on the tiny
// organised scene: a point hidden behind a nearer surface counts neither way, a point the sensor
// sees through counts against the match as the visibility metric counts it, and a pose must show
// at least half of its points.

#include <gtest/gtest.h>

#include "lmk/search/metrics/error_metrics.h"
#include "tests/landmark/tiny_organised_scene.h"

namespace lmk {
namespace {

constexpr double kBand = 0.02;  // the scene field's band: two coarse leaves of 1 cm

TEST(ProjectiveMetric, ThePatchWhereItWasSeenFitsWithFullCoverage) {
  const ErrorTerms t =
      evaluate_tiny("projective", tiny_landmark(), tiny_wall([](int, int) { return 1.0; }));
  EXPECT_EQ(t.support->unseen_points, 0u);
  EXPECT_EQ(t.landmark_to_scene_count, 9u);
  EXPECT_LT(t.error, 1e-3);
  EXPECT_DOUBLE_EQ(t.coverage(), 1.0);
}

// Column u = 18 is behind a plate 0.7 m away (30 cm in front: beyond the noise, and more than
// 5 cm outside the box): its three points are hidden and the other six alone decide, perfectly. The
// visibility metric charges the three as missing: about 1.6 cm each (their wall neighbours lie 2.5
// cm aside), 5 mm on average.
TEST(ProjectiveMetric, APointBehindANearerSurfaceIsHidden) {
  const Landmark landmark = tiny_landmark();
  const PointCloud scene =
      tiny_wall([](int u, int v) { return in_tiny_landmark(u, v) && u == 18 ? 0.7 : 1.0; });
  const ErrorTerms projective = evaluate_tiny("projective", landmark, scene);
  EXPECT_EQ(projective.support->unseen_points, 3u);
  EXPECT_EQ(projective.landmark_to_scene_count, 6u);
  EXPECT_LT(projective.error, 1e-3);
  EXPECT_DOUBLE_EQ(projective.coverage(), 1.0);
  const ErrorTerms visibility = evaluate_tiny("visibility", landmark, scene);
  EXPECT_EQ(visibility.landmark_to_scene_count, 9u);
  EXPECT_GT(visibility.error, 0.004);
  EXPECT_NEAR(visibility.coverage(), 6.0 / 9.0, 1e-12);
}

// Through column u = 18 the sensor sees a surface 1.3 m away, behind the points: they are not
// hidden, have no surface within 1 cm, and count against the match as in the visibility metric.
TEST(ProjectiveMetric, APointTheSensorSeesThroughCountsAgainstTheMatch) {
  const Landmark landmark = tiny_landmark();
  const PointCloud scene =
      tiny_wall([](int u, int v) { return in_tiny_landmark(u, v) && u == 18 ? 1.3 : 1.0; });
  const ErrorTerms projective = evaluate_tiny("projective", landmark, scene);
  const ErrorTerms visibility = evaluate_tiny("visibility", landmark, scene);
  EXPECT_EQ(projective.support->unseen_points, 0u);
  EXPECT_EQ(projective.landmark_to_scene_count, 9u);
  EXPECT_NEAR(projective.coverage(), 6.0 / 9.0, 1e-12);
  EXPECT_GT(projective.error, 0.004);
  EXPECT_DOUBLE_EQ(projective.error, visibility.error);
}

// A plate 3.5 cm in front of the patch, across its pixels, stands inside its box: an object that
// close may be the very one a false pose was fitted to, so it hides nothing. The nine points count
// as the visibility metric counts them (the plate is beyond the band), and the plate fills the
// free space.
TEST(ProjectiveMetric, ASurfaceInsideTheBoxHidesNothing) {
  const Landmark landmark = tiny_landmark();
  const PointCloud scene = tiny_wall(
      [](int u, int v) { return u >= 17 && u <= 21 && v >= 12 && v <= 16 ? 0.965 : 1.0; });
  const ErrorTerms t = evaluate_tiny("projective", landmark, scene);
  EXPECT_EQ(t.support->unseen_points, 0u);
  EXPECT_EQ(t.landmark_to_scene_count, 9u);
  EXPECT_GT(t.empty_space->violations, 0u);
  EXPECT_DOUBLE_EQ(t.coverage(), 0.0);
  EXPECT_DOUBLE_EQ(t.error, evaluate_tiny("visibility", landmark, scene).error);
}

// The whole patch behind a plate 0.7 m away: the pose shows none of the 4.5 points it must, and
// five count the band: its error is the band.
TEST(ProjectiveMetric, APoseHiddenEverywhereIsNoMatch) {
  const PointCloud scene =
      tiny_wall([](int u, int v) { return in_tiny_landmark(u, v) ? 0.7 : 1.0; });
  const ErrorTerms t = evaluate_tiny("projective", tiny_landmark(), scene);
  EXPECT_EQ(t.support->unseen_points, 9u);
  EXPECT_EQ(t.landmark_to_scene_count, 5u);
  EXPECT_NEAR(t.error, kBand, 1e-9);
  EXPECT_DOUBLE_EQ(t.coverage(), 0.0);
}

// Rows 13 and 14 hidden behind a plate 0.7 m away: three points shown where 4.5 are needed, so
// two more count the band: error (0 + 2 x 2 cm) / 5 = 8 mm, coverage 3 / 5.
TEST(ProjectiveMetric, APoseMustShowHalfOfItsPoints) {
  const PointCloud scene =
      tiny_wall([](int u, int v) { return in_tiny_landmark(u, v) && v <= 14 ? 0.7 : 1.0; });
  const ErrorTerms t = evaluate_tiny("projective", tiny_landmark(), scene);
  EXPECT_EQ(t.support->unseen_points, 6u);
  EXPECT_EQ(t.landmark_to_scene_count, 5u);
  EXPECT_NEAR(t.error, 2.0 * kBand / 5.0, 1e-3);
  EXPECT_NEAR(t.coverage(), 3.0 / 5.0, 1e-12);
}

}  // namespace
}  // namespace lmk
