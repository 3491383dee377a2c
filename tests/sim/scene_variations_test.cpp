// SPDX-License-Identifier: BSD-3-Clause
// The viewpoint and occlusion benchmarks' scenes: deterministic in their seed, within their
// ranges, and hiding what they are asked to hide (and no more).

#include "lmk/sim/scene_variations.h"

#include <gtest/gtest.h>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk {
namespace {

class SceneVariations : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    captured_ = new std::map<std::string, Landmark>();
    for (const BenchmarkLandmark& l : benchmark_landmarks()) {
      if (l.name == "bowl" || l.name == "cup" || l.name == "bowl_rim")
        captured_->emplace(l.name, capture_benchmark_landmark(l, false));
    }
  }
  static void TearDownTestSuite() { delete captured_; }

  // The hidden fraction of every first instance of the scene's in-context landmarks.
  static std::vector<double> hidden(const GeneratedScene& scene) {
    DepthSensorSettings exact;
    exact.noise = false;
    const PointCloud frame = render_depth(scene.mesh, scene.T_world_sensor, exact);
    std::vector<double> out;
    for (const std::string& name : scene.in_context)
      out.push_back(
          hidden_fraction(captured_->at(name), scene.instances.at(name).front(), frame, exact));
    return out;
  }

  static std::map<std::string, Landmark>* captured_;
};
std::map<std::string, Landmark>* SceneVariations::captured_ = nullptr;

TEST_F(SceneVariations, ANewViewpointKeepsToItsRangeAndSeesItsTarget) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const GeneratedScene original = make_scene("simple/bowl_and_cup", seed);
    GeneratedScene a = original, b = original;
    view_from_random_viewpoint(a, *captured_, 100 + seed);
    view_from_random_viewpoint(b, *captured_, 100 + seed);
    EXPECT_TRUE(a.T_world_sensor.isApprox(b.T_world_sensor, 0.0)) << "not deterministic";
    EXPECT_FALSE(a.T_world_sensor.isApprox(original.T_world_sensor, 1e-3)) << "did not move";
    const Eigen::Vector3d target =
        original.instances.at(original.in_context.front()).front().pose.translation();
    const double range = (a.T_world_sensor.translation() - target).norm();
    EXPECT_GE(range, ViewpointRange().min_range - 1e-9);
    EXPECT_LE(range, ViewpointRange().max_range + 1e-9);
    EXPECT_LE(hidden(a).front(), 0.5) << "seed " << seed;
    EXPECT_EQ(a.mesh.vertices.size(), original.mesh.vertices.size()) << "the world changed";
  }
}

TEST_F(SceneVariations, OccludersHideUpToWhatTheyAreAskedAndAreDeterministic) {
  OcclusionRange range;
  range.max_hidden = 0.4;
  double added = 0.0;
  int instances = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const GeneratedScene original = make_scene("simple/bowl_and_cup", seed);
    GeneratedScene a = original, b = original;
    add_occluders(a, *captured_, seed, range);
    add_occluders(b, *captured_, seed, range);
    EXPECT_EQ(a.mesh.vertices, b.mesh.vertices) << "not deterministic";
    EXPECT_GT(a.mesh.vertices.size(), original.mesh.vertices.size()) << "no occluder";
    const std::vector<double> before = hidden(original), after = hidden(a);
    for (std::size_t k = 0; k < before.size(); ++k) {
      // Hides something or nothing, never more than asked: the share of the seen points the
      // occluder covers is at most max_hidden (with a little slack for pixels at its edge).
      EXPECT_GE(after[k], before[k] - 0.02);
      EXPECT_LE(after[k] - before[k], range.max_hidden * (1.0 - before[k]) + 0.05);
      added += after[k] - before[k];
      ++instances;
    }
  }
  // Drawn uniformly up to 40%: about 20% on average.
  EXPECT_GT(added / instances, 0.08);
}

}  // namespace
}  // namespace lmk
