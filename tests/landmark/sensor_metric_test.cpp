// The sensor-aware metric's projective visibility, worked out by hand on a tiny organised scene: a
// 40 x 30 pinhole image of a wall 1 m away, and a landmark of nine of its points. A point behind a
// nearer surface is unknown, a point the sensor sees through counts the cap against the match.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "landmark/error_metrics.h"
#include "landmark/landmark.h"
#include "landmark/scene_index.h"

namespace lmk {
namespace {

constexpr int kWidth = 40, kHeight = 30;
constexpr double kF = 40.0, kCx = 19.5, kCy = 14.5;

Eigen::Vector3f on_ray(int u, int v, double depth) {
  return Eigen::Vector3f(static_cast<float>((u - kCx) / kF * depth),
                         static_cast<float>((v - kCy) / kF * depth), static_cast<float>(depth));
}

// The wall, with the depth of some pixels changed (NaN: no return).
PointCloud wall(const std::function<double(int, int)>& depth_at) {
  PointCloud cloud;
  cloud.width = kWidth;
  cloud.height = kHeight;
  for (int v = 0; v < kHeight; ++v)
    for (int u = 0; u < kWidth; ++u) cloud.points.push_back(on_ray(u, v, depth_at(u, v)));
  return cloud;
}

bool in_landmark(int u, int v) { return u >= 18 && u <= 20 && v >= 13 && v <= 15; }

struct Fixture {
  Landmark landmark;
  Fixture() {
    landmark.name = "patch";
    for (int v = 13; v <= 15; ++v)
      for (int u = 18; u <= 20; ++u) landmark.points.points.push_back(on_ray(u, v, 1.0));
    landmark.points.set_unorganized();
    landmark.box = Box(Eigen::Isometry3d(Eigen::Translation3d(0, 0, 1.0)), {0.2, 0.2, 0.1});
    landmark.sensor_origin = Eigen::Vector3d::Zero();  // captured from where the scene is seen
    prepare_landmark(landmark);
  }
  ErrorTerms evaluate(const PointCloud& scene) const {
    const SceneIndex index(scene);
    EXPECT_TRUE(index.range_image().has_value());
    const KdTree tree(landmark.points);
    return find_error_metric("sensor").evaluate(
        SceneView{index}, LandmarkView{landmark.points, tree, landmark.box, landmark},
        Eigen::Isometry3d::Identity());
  }
};

// The terms a case must give: unknown and seen-through points, the points counted, the error.
void expect_terms(const ErrorTerms& t, std::size_t unseen, std::size_t seen_through,
                  std::size_t counted, double error, double coverage) {
  EXPECT_EQ(t.unseen_points, unseen);
  EXPECT_EQ(t.seen_through_points, seen_through);
  EXPECT_EQ(t.landmark_to_scene_count, counted);
  EXPECT_NEAR(t.error, error, 1e-6);
  EXPECT_NEAR(t.coverage, coverage, 1e-12);
}

TEST(SensorMetric, ThePatchWhereItWasSeenHasNoErrorAndFullCoverage) {
  expect_terms(Fixture().evaluate(wall([](int, int) { return 1.0; })), 0, 0, 9, 0.0, 1.0);
}

// Column u = 18 is behind a surface 0.7 m away: its three points are unknown, and the other six
// alone decide, perfectly.
TEST(SensorMetric, APointBehindANearerSurfaceIsUnknown) {
  const auto depth = [](int u, int v) { return in_landmark(u, v) && u == 18 ? 0.7 : 1.0; };
  expect_terms(Fixture().evaluate(wall(depth)), 3, 0, 6, 0.0, 1.0);
}

// Through column u = 18 the sensor sees a surface 1.3 m away, 30 cm (over 30 sigma) behind the
// points: each of the three costs the cap of 3 sigma, so the error is 3 x 3 / 9 = 1 sigma and
// the coverage 6 / 9.
TEST(SensorMetric, APointTheSensorSeesThroughCountsAgainstTheMatch) {
  const auto depth = [](int u, int v) { return in_landmark(u, v) && u == 18 ? 1.3 : 1.0; };
  expect_terms(Fixture().evaluate(wall(depth)), 0, 3, 9, 1.0, 6.0 / 9.0);
}

// Where the sensor measured nothing there is no evidence either way.
TEST(SensorMetric, APointWithoutAReturnIsUnknown) {
  const auto depth = [](int u, int v) { return in_landmark(u, v) && v == 15 ? std::nan("") : 1.0; };
  expect_terms(Fixture().evaluate(wall(depth)), 3, 0, 6, 0.0, 1.0);
}

// Empty space, seen the same way. The patch was captured with the space in front of it free: with
// the wall where it was, the sensor sees through that space and confirms it. A plate 3.5 cm in
// front of the patch, across its pixels, stands in it: the voxels at the plate's depth are
// violated, and the patch behind it is unknown.
TEST(SensorMetric, EmptySpaceIsConfirmedWhereSeenThroughAndViolatedWhereASurfaceStands) {
  const Fixture f;
  ASSERT_GT(f.landmark.empty_space.size(), 0u);
  const ErrorTerms free = f.evaluate(wall([](int, int) { return 1.0; }));
  EXPECT_GT(free.empty_space_probes, 0u);
  EXPECT_EQ(free.empty_space_violations, 0u);
  EXPECT_GT(free.empty_space_observed, 0.0);
  const ErrorTerms blocked = f.evaluate(
      wall([](int u, int v) { return u >= 17 && u <= 21 && v >= 12 && v <= 16 ? 0.965 : 1.0; }));
  EXPECT_EQ(blocked.unseen_points, 9u);
  EXPECT_GT(blocked.empty_space_violations, 0u);
}

}  // namespace
}  // namespace lmk
