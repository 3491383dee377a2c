// SPDX-License-Identifier: BSD-3-Clause
// The paper's CandidateError (Algorithm 2) and the authors' variant on configurations whose errors
// can be worked out by hand.

#include "lmk/search/metrics/error_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/search/scene_index.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// A 3 x 3 grid of landmark points, 1 cm apart, in the plane z = 0, in a 10 cm box.
struct Fixture {
  PointCloud landmark_points;
  Box box{Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.1, 0.1, 0.1)};
  Fixture() {
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j) landmark_points.points.emplace_back(0.01f * i, 0.01f * j, 0.0f);
    landmark_points.set_unorganized();
  }
  ErrorTerms evaluate(const std::string& metric, const PointCloud& scene,
                      const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity(),
                      std::optional<double> threshold_range = std::nullopt) const {
    // The finest leaf lmk accepts, far below the 1 cm point spacing: each scene point has a voxel
    // of its own, so the index keeps it as it is.
    SceneSettings settings;
    settings.threshold_range = threshold_range;
    settings.leaf_size = settings.coarse_leaf = kMinLeafSize;
    settings.field_band = 2.0 * kMinLeafSize;
    const SceneIndex index(scene, settings);
    Landmark landmark;
    landmark.name = "grid";
    landmark.points = landmark_points;
    landmark.box = box;
    landmark.sensor_origin = Eigen::Vector3d(0, 0, 1);
    prepare_landmark(landmark);
    const KdTree landmark_tree(landmark_points);
    return find_error_metric(metric).evaluate(
        SceneView{index}, LandmarkView{landmark_points, landmark_tree, box, landmark}, T);
  }
};

TEST(PaperMetric, ZeroForAPerfectMatch) {
  const Fixture f;
  const ErrorTerms t = f.evaluate("paper", f.landmark_points);
  EXPECT_EQ(t.scene_points_in_box, 9u);
  EXPECT_EQ(t.scene_to_landmark_count, 9u);
  EXPECT_EQ(t.landmark_to_scene_count, 0u);  // every landmark point was visited
  EXPECT_DOUBLE_EQ(t.error, 0.0);
}

TEST(PaperMetric, APointInTheEmptyMarginRaisesTheErrorByExactlyItsDistance) {
  const Fixture f;
  PointCloud scene = f.landmark_points;
  scene.points.emplace_back(0.0f, 0.0f, 0.03f);  // 3 cm above the centre point, inside the box
  scene.set_unorganized();
  const ErrorTerms t = f.evaluate("paper", scene);
  EXPECT_EQ(t.scene_points_in_box, 10u);
  EXPECT_NEAR(t.scene_to_landmark_sum, 0.03, 1e-7);
  EXPECT_NEAR(t.error, 0.03 / 10.0, 1e-8);
  // Outside the box (6 cm up) the same point changes nothing.
  scene.points.back().z() = 0.06f;
  EXPECT_DOUBLE_EQ(f.evaluate("paper", scene).error, 0.0);
}

TEST(PaperMetric, UnvisitedLandmarkPointsAddTheirDistanceToTheWholeScene) {
  const Fixture f;
  // One scene point on the centre landmark point, and one far outside the box.
  const PointCloud scene({{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}});
  const ErrorTerms t = f.evaluate("paper", scene);
  EXPECT_EQ(t.scene_to_landmark_count, 1u);
  EXPECT_EQ(t.landmark_to_scene_count, 8u);
  // The 8 others are at 1 cm (4 edge neighbours) and sqrt(2) cm (4 corners) from the centre.
  const double expected_sum = 4 * 0.01 + 4 * 0.01 * std::sqrt(2.0);
  EXPECT_NEAR(t.landmark_to_scene_sum, expected_sum, 1e-7);
  EXPECT_NEAR(t.error, expected_sum / 9.0, 1e-8);
}

TEST(PaperMetric, EmptyBoxUsesTheWholeSceneAndAllEmptyIsInfinity) {
  const Fixture f;
  const PointCloud far({{0.3f, 0.0f, 0.0f}});
  const ErrorTerms t = f.evaluate("paper", far);
  EXPECT_EQ(t.scene_points_in_box, 0u);
  EXPECT_EQ(t.landmark_to_scene_count, 9u);
  double sum = 0;
  for (const auto& p : f.landmark_points.points) sum += (p - far.points[0]).norm();
  EXPECT_NEAR(t.error, sum / 9.0, 1e-7);
  ErrorTerms none;  // no term counted at all: no evidence of a match
  none.finish();
  EXPECT_TRUE(std::isinf(none.error));
  EXPECT_FALSE(std::isnan(none.error));
}

TEST(RapidMetric, SearchesOnlyTheBoxAndCapsAtFiveCentimetres) {
  const Fixture f;
  // In the box: the centre point. Outside: a point right next to a corner landmark point.
  const PointCloud scene({{0.0f, 0.0f, 0.0f}, {0.011f, 0.011f, 0.051f}});
  const ErrorTerms t = f.evaluate("rapid", scene);
  EXPECT_EQ(t.scene_points_in_box, 1u);
  // The unvisited points look only at the centre point: 1 cm and sqrt(2) cm, all under 5 cm.
  EXPECT_EQ(t.landmark_to_scene_count, 8u);
  EXPECT_NEAR(t.landmark_to_scene_sum, 4 * 0.01 + 4 * 0.01 * std::sqrt(2.0), 1e-7);
  // With nothing in the box there is nothing to count: infinity, not NaN.
  EXPECT_TRUE(std::isinf(f.evaluate("rapid", PointCloud({{0.3f, 0.0f, 0.0f}})).error));
}

TEST(RapidMetric, DropsDistancesOfFiveCentimetresOrMore) {
  Fixture f;
  f.box.size << 0.2, 0.2, 0.2;
  // One scene point 6 cm above the centre: every landmark point is at least 6 cm from it.
  const PointCloud scene({{0.0f, 0.0f, 0.06f}});
  const ErrorTerms rapid = f.evaluate("rapid", scene);
  EXPECT_EQ(rapid.scene_to_landmark_count, 1u);
  EXPECT_EQ(rapid.landmark_to_scene_count, 0u);
  EXPECT_NEAR(rapid.error, 0.06, 1e-7);
  EXPECT_EQ(f.evaluate("paper", scene).landmark_to_scene_count, 8u);  // paper counts them all
}

TEST(Metrics, InvariantUnderARigidMotionOfSceneAndCandidate) {
  const Fixture f;
  PointCloud scene = test::random_cloud(500, 5, 0.08f);
  const Eigen::Isometry3d T = pose_from_xyz_rpy({0.4, -0.3, 1.2}, {0.5, -0.4, 2.0});
  PointCloud moved = scene;
  for (auto& p : moved.points) p = (T.cast<float>() * p);
  for (const char* metric : {"paper", "rapid"}) {
    const ErrorTerms a = f.evaluate(metric, scene), b = f.evaluate(metric, moved, T);
    EXPECT_EQ(a.scene_points_in_box, b.scene_points_in_box) << metric;
    EXPECT_NEAR(a.error, b.error, 1e-6) << metric;
  }
}

TEST(VisibilityMetric, BeyondTheThresholdRangeTheErrorIsScaledAsTheNoiseGrows) {
  const Fixture f;
  // The landmark 2.5 m in front of the scene's sensor (at the origin), its scene copy 2 mm off.
  const Eigen::Isometry3d T = pose_from_xyz_rpy({0.0, 0.0, 2.5}, {0.0, 0.0, 0.0});
  PointCloud scene = f.landmark_points;
  for (auto& p : scene.points) p = T.cast<float>() * p + Eigen::Vector3f(0.0f, 0.0f, 0.002f);
  for (const char* metric : {"visibility", "projective"}) {
    const ErrorTerms fixed = f.evaluate(metric, scene, T);
    EXPECT_EQ(fixed.range_scale, 1.0) << metric;
    const ErrorTerms nearer = f.evaluate(metric, scene, T, 3.0);  // 2.5 m is within 3 m
    EXPECT_EQ(nearer.range_scale, 1.0) << metric;
    EXPECT_EQ(nearer.error, fixed.error) << metric;
    const ErrorTerms scaled = f.evaluate(metric, scene, T, 1.5);
    SceneSettings settings;
    settings.leaf_size = settings.coarse_leaf = kMinLeafSize;
    settings.threshold_range = 1.5;
    EXPECT_NEAR(scaled.range_scale, match_error_scale(settings, 2.5), 1e-9) << metric;
    EXPECT_LT(scaled.range_scale, 1.0) << metric;
    EXPECT_NEAR(scaled.error, scaled.range_scale * fixed.error, 1e-12) << metric;
    // The sums are the metric's own, unscaled: a reader sees what was measured.
    EXPECT_EQ(scaled.landmark_to_scene_sum, fixed.landmark_to_scene_sum) << metric;
  }
  // The paper's metrics are never scaled.
  EXPECT_EQ(f.evaluate("paper", scene, T, 1.5).range_scale, 1.0);
}

TEST(VisibilityMetric, ATrueMatchsExpectedErrorGrowsWithTheDepthNoise) {
  SceneSettings settings;
  double previous = 0.0;
  for (double range : {0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5}) {
    const double e = expected_match_error(settings, range);
    EXPECT_GT(e, previous) << range;
    previous = e;
  }
  // Near the sensor the coarse leaf's resolution dominates; far away, the noise.
  EXPECT_NEAR(expected_match_error(settings, 0.0), 0.28 * settings.coarse_leaf, 1e-12);
  EXPECT_GT(expected_match_error(settings, 3.0), 0.4 * settings.depth_noise().measurement_sigma(3));
  settings.threshold_range = 2.0;
  EXPECT_EQ(match_error_scale(settings, 1.0), 1.0);
  EXPECT_NEAR(match_error_scale(settings, 3.0),
              expected_match_error(settings, 2.0) / expected_match_error(settings, 3.0), 1e-12);
}

// Every registered metric, on the L-shape's own capture scene: below its default threshold at the
// true pose, and rising as the candidate slides 1 cm, then 3 cm, along the table. A metric added
// to the registry is held to this without a test of its own.
TEST(Metrics, EveryRegisteredMetricIsLowAtTheTruePoseAndRisesWithAnOffset) {
  using namespace test_scenes;
  const Eigen::Vector2d xy = kCopies[0];
  const PointCloud scene = render_scene({xy}, true);
  const Landmark landmark = capture(scene, box_at(xy), "L");
  const SceneIndex index(scene, SceneSettings{});
  const KdTree tree(landmark.points);
  const std::vector<float> empty = empty_space_distances(landmark, tree);
  LandmarkView view{landmark.points, tree, landmark.box, landmark};
  view.empty_distances = &empty;
  for (const ErrorMetric& metric : error_metrics()) {
    const auto error_at = [&](double offset) {
      const Eigen::Isometry3d T(Eigen::Translation3d(offset, 0.0, 0.0));
      return metric.evaluate(SceneView{index}, view, T).error;
    };
    const double at_truth = error_at(0.0), at_1cm = error_at(0.01), at_3cm = error_at(0.03);
    EXPECT_LT(at_truth, metric.default_threshold) << metric.name;
    EXPECT_LT(at_truth, at_1cm) << metric.name;
    EXPECT_LT(at_1cm, at_3cm) << metric.name;
  }
}

TEST(Metrics, RegistryFindsByNameAndNamesTheKnownOnes) {
  EXPECT_EQ(find_error_metric("paper").name, "paper");
  EXPECT_EQ(find_error_metric("rapid").name, "rapid");
  try {
    find_error_metric("nope");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("known: paper, rapid"), std::string::npos) << e.what();
  }
}

// docs/library.md's table of metrics ("| `name` | threshold | what |" rows under "### Error
// metrics") names exactly the registered metrics, in the registry's order, with their thresholds.
TEST(ErrorMetrics, TheLibraryDocsListEveryRegisteredMetric) {
  const std::string docs = test::read_bytes(std::string(LMK_SOURCE_DIR) + "/docs/library.md");
  const std::size_t section = docs.find("### Error metrics");
  ASSERT_NE(section, std::string::npos);
  std::vector<std::string> listed;
  std::vector<std::string> thresholds;
  std::size_t at = docs.find("\n| `", section);
  while (at != std::string::npos && at < docs.find("\n## ", section)) {
    const std::size_t name_end = docs.find('`', at + 4);
    listed.push_back(docs.substr(at + 4, name_end - at - 4));
    const std::size_t cell = docs.find("| ", name_end) + 2;
    thresholds.push_back(docs.substr(cell, docs.find(" |", cell) - cell));
    at = docs.find("\n| `", name_end);
  }
  std::vector<std::string> registered;
  for (const ErrorMetric& m : error_metrics()) {
    registered.push_back(m.name);
    const double shown = m.display.scale * m.default_threshold;
    const std::size_t row = registered.size() - 1;
    if (row < thresholds.size()) {
      EXPECT_DOUBLE_EQ(std::stod(thresholds[row]), shown) << m.name << ": " << thresholds[row];
    }
  }
  EXPECT_EQ(listed, registered);
}

}  // namespace
}  // namespace lmk
