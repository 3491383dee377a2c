// SPDX-License-Identifier: BSD-3-Clause
// The sensor-aware metric's projective visibility, worked out by hand on a tiny organised scene: a
// 40 x 30 pinhole image of a wall 1 m away, and a landmark of nine of its points. A point behind a
// nearer surface is unknown, a point the sensor sees through counts the cap against the match.

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/search/metrics/error_metrics.h"
#include "tests/landmark/tiny_organised_scene.h"

namespace lmk {
namespace {

struct TinyWallFixture {
  Landmark landmark = tiny_landmark();
  ErrorTerms evaluate(const PointCloud& scene) const {
    return evaluate_tiny("sensor", landmark, scene);
  }
};

// The terms a case must give: unknown and seen-through points, the points counted, the error.
void expect_terms(const ErrorTerms& t, std::size_t unseen, std::size_t seen_through,
                  std::size_t counted, double error, double coverage) {
  EXPECT_EQ(t.support->unseen_points, unseen);
  EXPECT_EQ(t.support->seen_through_points, seen_through);
  EXPECT_EQ(t.landmark_to_scene_count, counted);
  EXPECT_NEAR(t.error, error, 1e-6);
  EXPECT_NEAR(t.coverage(), coverage, 1e-12);
}

TEST(SensorMetric, ThePatchWhereItWasSeenHasNoErrorAndFullCoverage) {
  expect_terms(TinyWallFixture().evaluate(tiny_wall([](int, int) { return 1.0; })), 0, 0, 9, 0.0,
               1.0);
}

// Column u = 18 is behind a surface 0.7 m away: its three points are unknown, and the other six
// alone decide, perfectly.
TEST(SensorMetric, APointBehindANearerSurfaceIsUnknown) {
  const auto depth = [](int u, int v) { return in_tiny_landmark(u, v) && u == 18 ? 0.7 : 1.0; };
  expect_terms(TinyWallFixture().evaluate(tiny_wall(depth)), 3, 0, 6, 0.0, 1.0);
}

// Through column u = 18 the sensor sees a surface 1.3 m away, 30 cm (over 30 sigma) behind the
// points: each of the three costs the cap of 3 sigma, so the error is 3 x 3 / 9 = 1 sigma and
// the coverage 6 / 9.
TEST(SensorMetric, APointTheSensorSeesThroughCountsAgainstTheMatch) {
  const auto depth = [](int u, int v) { return in_tiny_landmark(u, v) && u == 18 ? 1.3 : 1.0; };
  expect_terms(TinyWallFixture().evaluate(tiny_wall(depth)), 0, 3, 9, 1.0, 6.0 / 9.0);
}

// Where the sensor measured nothing there is no evidence either way.
TEST(SensorMetric, APointWithoutAReturnIsUnknown) {
  const auto depth = [](int u, int v) {
    return in_tiny_landmark(u, v) && v == 15 ? std::nan("") : 1.0;
  };
  expect_terms(TinyWallFixture().evaluate(tiny_wall(depth)), 3, 0, 6, 0.0, 1.0);
}

// Empty space, seen the same way. The patch was captured with the space in front of it free: with
// the wall where it was, the sensor sees through that space and confirms it. A plate 3.5 cm in
// front of the patch, across its pixels, stands in it: the voxels at the plate's depth are
// violated, and the patch behind it is unknown.
TEST(SensorMetric, EmptySpaceIsConfirmedWhereSeenThroughAndViolatedWhereASurfaceStands) {
  const TinyWallFixture f;
  ASSERT_GT(f.landmark.empty_space.size(), 0u);
  const ErrorTerms free = f.evaluate(tiny_wall([](int, int) { return 1.0; }));
  EXPECT_GT(free.empty_space->probes, 0u);
  EXPECT_EQ(free.empty_space->violations, 0u);
  EXPECT_GT(free.empty_space->observed, 0.0);
  const ErrorTerms blocked = f.evaluate(tiny_wall(
      [](int u, int v) { return u >= 17 && u <= 21 && v >= 12 && v <= 16 ? 0.965 : 1.0; }));
  EXPECT_EQ(blocked.support->unseen_points, 9u);
  EXPECT_GT(blocked.empty_space->violations, 0u);
}

}  // namespace
}  // namespace lmk
