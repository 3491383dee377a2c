// SPDX-License-Identifier: BSD-3-Clause
// The benchmark datasets: deterministic for a preset and seed, ground truth on the scene surface,
// landmarks captured as a user would, and clear errors for bad requests.

#include "lmk/datasets/benchmark_dataset.h"

#include <gtest/gtest.h>

#include <numeric>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/find_landmark.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// The free space is carved from the capture scene, which a landmark file does not hold: the same
// points with other free space are another dataset, or a cached evaluation would outlive it.
TEST(BenchmarkDataset, TheFingerprintFollowsTheLandmarksFreeSpace) {
  test::ScratchDir dir;
  GenerateOptions options;
  options.types = {"simple/bowl_and_cup"};
  const Dataset dataset = generate_benchmark_dataset(dir.path().string(), "paper", options);
  std::vector<Landmark> landmarks;
  for (const DatasetLandmark& entry : dataset.landmarks)
    landmarks.push_back(load_landmark((dir.path() / entry.file).string()));
  const std::string before = dataset_fingerprint(dir.path().string(), dataset, landmarks);
  EXPECT_EQ(before, dataset_fingerprint(dir.path().string(), dataset));
  const std::size_t voxels = landmarks[0].empty_space.size();
  prepare_landmark(landmarks[0]);  // rays to its own points only: less space observed free
  ASSERT_NE(landmarks[0].empty_space.size(), voxels);
  EXPECT_NE(dataset_fingerprint(dir.path().string(), dataset, landmarks), before);
}

// With views, each landmark is also NAME-v2, fused from two demonstration views, and searched in
// the same pairs as NAME; one view is the dataset it always was.
TEST(BenchmarkDataset, ViewsAddLandmarksOfSeveralViewsWithTheSamePairs) {
  test::ScratchDir one, two;
  GenerateOptions options;
  options.types = {"simple/bowl_and_cup"};
  const Dataset d1 = generate_benchmark_dataset(one.path().string(), "paper", options);
  options.views = 2;
  const Dataset d2 = generate_benchmark_dataset(two.path().string(), "paper", options);
  std::vector<std::string> names;
  for (const DatasetLandmark& l : d2.landmarks) names.push_back(l.name);
  EXPECT_EQ(names, (std::vector<std::string>{"bowl", "bowl-v2", "cup", "cup-v2"}));
  const Landmark cup = load_landmark((one.path() / "landmarks/cup.lmk").string());
  const Landmark cup2 = load_landmark((two.path() / "landmarks/cup-v2.lmk").string());
  EXPECT_FALSE(cup.multi_view());
  ASSERT_EQ(cup2.view_count(), 2u);
  EXPECT_GT(cup2.points.size(), cup.points.size());
  // The first view's points are the one-view landmark's.
  for (std::size_t i = 0; i < cup.points.size(); ++i) {
    ASSERT_EQ(cup2.points.points[i], cup.points.points[i]);
  }
  ASSERT_EQ(d2.scenes.size(), d1.scenes.size());
  for (std::size_t s = 0; s < d1.scenes.size(); ++s) {
    ASSERT_EQ(d2.scenes[s].pairs.size(), 2 * d1.scenes[s].pairs.size());
    for (std::size_t k = 0; k < d1.scenes[s].pairs.size(); ++k) {
      const DatasetPair& a = d1.scenes[s].pairs[k];
      const DatasetPair& b = d2.scenes[s].pairs[2 * k + 1];
      EXPECT_EQ(b.landmark, a.landmark + "-v2");
      EXPECT_EQ(b.in_context, a.in_context);
      ASSERT_EQ(b.instances.size(), a.instances.size());
      for (std::size_t i = 0; i < a.instances.size(); ++i) {
        EXPECT_TRUE(b.instances[i].isApprox(a.instances[i], 1e-9));
      }
    }
  }
  EXPECT_EQ(test::read_bytes((one.path() / d1.scenes[0].file).string()),
            test::read_bytes((two.path() / d2.scenes[0].file).string()));
}

TEST(BenchmarkDataset, TheSamePresetAndSeedWriteTheSameContent) {
  test::ScratchDir a, b, c;
  GenerateOptions options;
  options.types = {"simple/bowl_and_cup", "unconventional/drawer"};
  const Dataset da = generate_benchmark_dataset(a.path().string(), "paper", options);
  const Dataset db = generate_benchmark_dataset(b.path().string(), "paper", options);
  EXPECT_EQ(dataset_fingerprint(a.path().string(), da), dataset_fingerprint(b.path().string(), db));
  // Another seed is another dataset.
  options.first_seed = 2;
  const Dataset dc = generate_benchmark_dataset(c.path().string(), "paper", options);
  EXPECT_NE(dataset_fingerprint(a.path().string(), da), dataset_fingerprint(c.path().string(), dc));
  // What was written is a valid dataset, and reads back as written.
  const Dataset loaded = load_dataset(a.path().string());
  ASSERT_EQ(loaded.scenes.size(), 2u);
  EXPECT_EQ(loaded.scenes[0].name, "simple-bowl_and_cup-1");
  ASSERT_TRUE(loaded.scenes[0].up.has_value());
  EXPECT_NEAR(loaded.scenes[0].up->z(), 1.0, 1e-12);
  std::vector<std::string> names;
  for (const DatasetLandmark& l : loaded.landmarks) names.push_back(l.name);
  EXPECT_EQ(names, (std::vector<std::string>{"bowl", "cup", "drawer_handle"}));
  // The scene file is an organised Kinect frame carrying its sensor pose.
  const PointCloud cloud = read_cloud((a.path() / loaded.scenes[0].file).string());
  EXPECT_EQ(cloud.width, 640u);
  EXPECT_EQ(cloud.height, 480u);
  EXPECT_TRUE(cloud.T_cloud_sensor.isApprox(loaded.scenes[0].T_scene_sensor, 1e-5));
}

// Every instance records how much of it the scene's sensor does not see; an unoccluded one in
// plain view (a standalone cup) little, the ball inside touching bowls much.
TEST(BenchmarkDataset, InstancesRecordTheirHiddenFraction) {
  test::ScratchDir dir;
  GenerateOptions options;
  options.types = {"simple/bowl_and_cup", "cluttered/bowls_in_contact"};
  const Dataset d = generate_benchmark_dataset(dir.path().string(), "paper", options);
  std::size_t recorded = 0;
  for (const DatasetScene& s : d.scenes) {
    for (const DatasetPair& p : s.pairs) {
      ASSERT_EQ(p.hidden.size(), p.instances.size()) << s.name << " " << p.landmark;
      for (double h : p.hidden) {
        EXPECT_GE(h, 0.0);
        EXPECT_LE(h, 1.0);
        ++recorded;
      }
    }
  }
  EXPECT_GT(recorded, 4u);
  EXPECT_LT(d.pair(d.scenes[0], "cup").hidden.at(0), 0.2);
  EXPECT_GT(d.pair(d.scenes[1], "ball").hidden.at(0), 0.4);
}

TEST(BenchmarkDataset, PresetsAndTheirSizes) {
  EXPECT_EQ(benchmark_preset("paper").seeds, 1);
  EXPECT_EQ(benchmark_preset("paper-x10").seeds, 10);
  EXPECT_EQ(benchmark_preset("paper-x100").seeds, 100);
  EXPECT_TRUE(benchmark_preset("rotations").hard);
  try {
    benchmark_preset("papers");
    FAIL() << "an unknown preset was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("paper-x10"), std::string::npos) << e.what();
  }
  test::ScratchDir dir;
  GenerateOptions options;
  options.types = {"simple/nothing"};
  EXPECT_THROW(generate_benchmark_dataset(dir.path().string(), "paper", options), Error);
}

// Every landmark, captured without noise, moved onto each ground-truth instance of it in every
// scene type (noiseless, seed 1, and a hard variant), lies on the world's surface: its points'
// mean distance to the scene mesh is below 5 mm.
TEST(BenchmarkDataset, GroundTruthPosesPutTheLandmarkOnTheSceneSurface) {
  std::map<std::string, Landmark> landmarks;
  for (const auto* list : {&benchmark_landmarks(), &colour_landmarks()}) {
    for (const BenchmarkLandmark& l : *list)
      landmarks.emplace(l.name, capture_benchmark_landmark(l, false));
  }
  std::vector<std::string> types = scene_types();
  types.insert(types.end(), colour_scene_types().begin(), colour_scene_types().end());
  std::size_t checked = 0;
  for (const bool hard : {false, true}) {
    for (const std::string& type : types) {
      const GeneratedScene scene = make_scene(type, 1, hard);
      for (const auto& [name, boxes] : scene.instances) {
        const Landmark& landmark = landmarks.at(name);
        for (const Box& truth : boxes) {
          // T_scene_capture takes the capture box onto the ground-truth box.
          const Eigen::Isometry3d T = truth.pose * landmark.box.pose.inverse();
          std::vector<Eigen::Vector3d> moved;
          for (const auto& p : landmark.points.points) moved.push_back(T * p.cast<double>());
          const std::vector<double> d = distances_to_mesh(scene.mesh, moved);
          const double mean = std::accumulate(d.begin(), d.end(), 0.0) / d.size();
          EXPECT_LT(mean, 0.005) << type << (hard ? " (hard)" : "") << ": " << name;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 80u);
}

// The colour look-alikes (issue #35): one shape in several colours, the landmark's colour kept in
// its file, and a search that tells the landmark's colour from the others' where shape alone
// cannot.
TEST(BenchmarkDataset, TheColourPresetPaintsOneShapeInSeveralColours) {
  test::ScratchDir dir;
  GenerateOptions options;
  options.types = {"colour/cups"};
  options.seeds = 2;
  const Dataset d = generate_benchmark_dataset(dir.path().string(), "colours", options);
  ASSERT_EQ(d.landmarks.size(), 1u);
  EXPECT_EQ(d.landmarks[0].name, "red_cup");
  const Landmark cup = load_landmark((dir.path() / d.landmarks[0].file).string());
  ASSERT_TRUE(cup.points.has_colors());
  std::size_t red = 0;
  for (const Color& c : cup.points.colors) red += c.r > 2 * c.g && c.r > 2 * c.b;
  EXPECT_GT(red, cup.points.size() / 2);
  ASSERT_EQ(d.scenes.size(), 2u);
  for (const DatasetScene& entry : d.scenes) {
    SCOPED_TRACE(entry.name);
    const PointCloud scene = read_cloud((dir.path() / entry.file).string());
    ASSERT_TRUE(scene.has_colors());
    const std::vector<Eigen::Isometry3d> truth = d.pair(entry, "red_cup").instances;
    ASSERT_FALSE(truth.empty());
    const auto correct = [&](const Match& m) {
      return std::any_of(truth.begin(), truth.end(), [&](const Eigen::Isometry3d& t) {
        return (t.translation() - m.box.pose.translation()).norm() < 0.02;
      });
    };
    FindSettings shape_only;
    shape_only.selection.colour_weight = 0.0;
    const FindResult by_shape = find_landmark(scene, cup, shape_only);
    const FindResult by_colour = find_landmark(scene, cup, FindSettings{});  // colour by default
    EXPECT_GT(std::count_if(by_shape.matches.begin(), by_shape.matches.end(),
                            [&](const Match& m) { return !correct(m); }),
              0);
    EXPECT_EQ(by_colour.matches.size(), truth.size());
    for (const Match& m : by_colour.matches) EXPECT_TRUE(correct(m));
    EXPECT_GT(by_colour.stats.rejected[RejectionReason::colour_differs], 0u);
  }
}

}  // namespace
}  // namespace lmk
