// SPDX-License-Identifier: BSD-3-Clause
// SceneSettings::unseen_points on the tiny organised wall, worked out by hand: a landmark point
// the scene's sensor could not see (beyond the image's edge, on a pixel without a return) counts
// against the match by default, and neither way when the setting says so.

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/search/scene_index.h"
#include "tests/landmark/tiny_organised_scene.h"

namespace lmk {
namespace {

SceneSettings unseen(UnseenPoints which) {
  SceneSettings s;
  s.unseen_points = which;
  return s;
}

constexpr double kFieldBand = 0.02;  // the scene field's band: two coarse leaves of 1 cm
const auto kWall = [](int, int) { return 1.0; };

// Column u = 18 of the patch has no return: counted, its three points cost the distance to the
// wall's next pixels (2.5 cm aside); with `no-return` the other six decide, perfectly. The image
// still holds the pixels, so `outside-image` counts them as by default.
TEST(UnseenPoints, APointOnAPixelWithoutAReturnCountsOnlyWhenAsked) {
  const PointCloud scene =
      tiny_wall([](int u, int v) { return in_tiny_landmark(u, v) && u == 18 ? NAN : 1.0; });
  const Landmark landmark = tiny_landmark();
  for (const char* metric : {"visibility", "projective"}) {
    SCOPED_TRACE(metric);
    const ErrorTerms counted = evaluate_tiny(metric, landmark, scene);
    EXPECT_EQ(counted.support->unseen_points, 0u);
    EXPECT_EQ(counted.landmark_to_scene_count, 9u);
    EXPECT_GT(counted.error, 0.004);
    const ErrorTerms no_return =
        evaluate_tiny(metric, landmark, scene, unseen(UnseenPoints::no_return));
    EXPECT_EQ(no_return.support->unseen_points, 3u);
    EXPECT_EQ(no_return.landmark_to_scene_count, 6u);
    EXPECT_LT(no_return.error, 1e-3);
    EXPECT_DOUBLE_EQ(no_return.coverage(), 1.0);
    EXPECT_DOUBLE_EQ(
        evaluate_tiny(metric, landmark, scene, unseen(UnseenPoints::outside_image)).error,
        counted.error);
  }
}

// The image ends after column 19: the patch's column u = 20 lies beyond its edge. Counted, its
// three points cost the distance to column 19; with `outside-image` (or `no-return`, which includes
// it) they count neither way.
TEST(UnseenPoints, APointBeyondTheImagesEdgeCountsOnlyWhenAsked) {
  const PointCloud scene = tiny_wall(kWall, 20);
  const Landmark landmark = tiny_landmark();
  const ErrorTerms counted = evaluate_tiny("visibility", landmark, scene);
  EXPECT_EQ(counted.landmark_to_scene_count, 9u);
  EXPECT_GT(counted.error, 0.004);
  for (UnseenPoints which : {UnseenPoints::outside_image, UnseenPoints::no_return}) {
    const ErrorTerms t = evaluate_tiny("visibility", landmark, scene, unseen(which));
    EXPECT_EQ(t.support->unseen_points, 3u);
    EXPECT_EQ(t.landmark_to_scene_count, 6u);
    EXPECT_LT(t.error, 1e-3);
  }
}

// A pose must still show half the landmark: the image ending after column 18 leaves three of the
// nine points in it, so two more count the band, as when the rest is hidden behind an occluder.
TEST(UnseenPoints, APoseMustStillShowHalfOfItsPoints) {
  const ErrorTerms t = evaluate_tiny("visibility", tiny_landmark(), tiny_wall(kWall, 19),
                                     unseen(UnseenPoints::outside_image));
  EXPECT_EQ(t.support->unseen_points, 6u);
  EXPECT_EQ(t.landmark_to_scene_count, 5u);
  EXPECT_NEAR(t.error, 2.0 * kFieldBand / 5.0, 1e-3);
}

// An unorganised scene has no image to fall outside of, nor pixels: every point counts.
TEST(UnseenPoints, AnUnorganisedSceneCountsEveryPoint) {
  PointCloud scene = tiny_wall(kWall, 20);
  scene.set_unorganized();
  const SceneIndex index(scene, unseen(UnseenPoints::no_return));
  ASSERT_FALSE(index.organised());
  EXPECT_FALSE(unseen_by_sensor(index, on_tiny_ray(25, 14, 1.0), UnseenPoints::no_return));
}

}  // namespace
}  // namespace lmk
