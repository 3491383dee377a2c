// SPDX-License-Identifier: BSD-3-Clause
// The footprint estimate against the measured peak (issue #47): lmk serve admits a search by it,
// so it must not fall below what indexing and searching a scene take, on scenes whose memory
// grows with their points in different ways (surfaces, points scattered near and far, an
// organised frame). The peak is measured as the growth of this process's high-water mark, reset
// before each scene (/proc/self/clear_refs; each test case runs in its own process).
#include "lmk/search/scene_footprint.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <random>
#include <string>

#include "lmk/geometry/cloud_io.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/landmark_index.h"
#include "lmk/search/scene_index.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

FindSettings settings_for(const PointCloud& scene) {
  FindSettings s;
  s.scene.base_frame = !scene.is_organized();
  s.execution.threads = 2;
  return s;
}

// The growth of the peak resident memory while `scene` is indexed, its fine level built and the
// cup searched in it.
double measured_peak(const PointCloud& scene, const LandmarkIndex& cup, const FindSettings& s) {
  const double before = test::process_status_bytes("VmRSS");
  {
    const SceneIndex index(scene, s.scene);
    index.fine_tree();
    index.coarse_tree();
    const FindResult found = find_landmark(index, cup, s);
    EXPECT_GE(found.stats.seeds, 0u);
  }
  return test::process_status_bytes("VmHWM") - before;
}

PointCloud surfaces(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-2.0f, 2.0f), h(0.0f, 2.5f);
  std::normal_distribution<float> noise(0.0f, 0.002f);
  PointCloud c;
  c.points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3f p;
    switch (i % 4) {
      case 0:
        p = {u(rng), u(rng), 0.0f};  // the floor
        break;
      case 1:
        p = {u(rng), 2.0f, h(rng)};  // two walls
        break;
      case 2:
        p = {2.0f, u(rng), h(rng)};
        break;
      default:
        p = {0.3f * u(rng), 0.2f * u(rng), 0.75f};  // a table top
    }
    c.points.push_back(p + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
  }
  c.set_unorganized();
  return c;
}

PointCloud scattered(std::size_t n, float side, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-side / 2, side / 2);
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) c.points.emplace_back(u(rng), u(rng), u(rng) + side / 2);
  c.set_unorganized();
  return c;
}

void expect_estimate_bounds_peak(const std::string& what, const PointCloud& scene) {
  if (!test::reset_peak_memory()) GTEST_SKIP() << "/proc/self/clear_refs cannot be written here";
  const Landmark cup_landmark = load_landmark(LMK_SOURCE_DIR "/tests/cli/fixtures/cup_v2.lmk");
  const FindSettings s = settings_for(scene);
  const LandmarkIndex cup(cup_landmark, s);
  const SceneFootprint f = estimate_scene_footprint(scene, s.scene);
  ASSERT_TRUE(test::reset_peak_memory());
  const double peak = measured_peak(scene, cup, s);
  std::printf(
      "%s: %zu points, %zu coarse voxels, %zu field nodes, %zu occupancy nodes: estimate %.0f MB, "
      "measured %.0f MB\n",
      what.c_str(), f.points, f.coarse_voxels, f.field_nodes, f.occupancy_nodes, f.bytes / 1e6,
      peak / 1e6);
  EXPECT_FALSE(f.over_limit);
  EXPECT_GE(static_cast<double>(f.bytes), peak) << what << ": the estimate is below the peak";
  // And not so far above that it refuses what would fit: a price, not a guess.
  EXPECT_LE(static_cast<double>(f.bytes), 2.5 * peak + 64e6) << what;
}

TEST(SceneFootprint, TheEstimateBoundsThePeakOfSurfaces) {
  std::mt19937 rng(1);
  expect_estimate_bounds_peak("surfaces", surfaces(1'000'000, rng));
}

TEST(SceneFootprint, TheEstimateBoundsThePeakOfPointsScatteredInARoom) {
  std::mt19937 rng(2);
  expect_estimate_bounds_peak("scattered in 3 m", scattered(600'000, 3.0f, rng));
}

TEST(SceneFootprint, TheEstimateBoundsThePeakOfPointsScatteredFarApart) {
  // Each point alone in its band: about 3 field nodes (13 KB) per point.
  std::mt19937 rng(3);
  expect_estimate_bounds_peak("scattered in 40 m", scattered(20'000, 40.0f, rng));
}

TEST(SceneFootprint, TheEstimateBoundsThePeakOfAnOrganisedFrame) {
  expect_estimate_bounds_peak("organised frame",
                              test_scenes::render_scene(test_scenes::kCopies, true));
}

// A scene given as a file (LMK_FOOTPRINT_CLOUD): how the estimate was calibrated on 5-million-point
// scenes, kept out of CI.
TEST(SceneFootprint, TheEstimateBoundsThePeakOfAGivenCloud) {
  const char* path = std::getenv("LMK_FOOTPRINT_CLOUD");
  if (path == nullptr) GTEST_SKIP() << "set LMK_FOOTPRINT_CLOUD to a cloud file";
  expect_estimate_bounds_peak(path, read_cloud(path));
}

TEST(SceneFootprint, CountingStopsAtTheLimit) {
  std::mt19937 rng(4);
  const PointCloud far = scattered(200'000, 100.0f, rng);
  const SceneFootprint f = estimate_scene_footprint(far, SceneSettings{}, 500'000'000);
  EXPECT_TRUE(f.over_limit);
  EXPECT_GT(f.bytes, 500'000'000u);
  EXPECT_LT(f.field_nodes, 200'000u);  // stopped near 500 MB of nodes, far before the 600 000
  const SceneFootprint whole = estimate_scene_footprint(far, SceneSettings{});
  EXPECT_FALSE(whole.over_limit);
  EXPECT_GT(whole.field_nodes, 400'000u);
  EXPECT_GT(whole.bytes, 2'000'000'000u);
}

// Issue #47: indexing checks for a stop between pieces of its work, often enough that a cancelled
// search ends within about 200 ms, and ends at the check that throws.
struct Stopped {};

TEST(StopCheck, IndexingChecksThroughoutAndEndsAtTheCheckThatThrows) {
  std::mt19937 rng(5);
  const PointCloud scene = scattered(1'000'000, 3.0f, rng);
  using Clock = std::chrono::steady_clock;
  std::mutex mutex;
  std::size_t checks = 0;
  double longest = 0.0;
  Clock::time_point last = Clock::now();
  const Clock::time_point begin = last;
  {
    const SceneIndex index(scene, SceneSettings{}, [&] {
      std::lock_guard<std::mutex> lock(mutex);
      const Clock::time_point now = Clock::now();
      longest = std::max(longest, std::chrono::duration<double>(now - last).count());
      last = now;
      ++checks;
    });
    index.fine_tree();
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  std::printf("indexing 1 million scattered points: %zu checks in %.2f s, longest gap %.0f ms\n",
              checks, seconds, 1000.0 * longest);
  // Every point loop checks each kItemsPerStopCheck points: the occupancy, the moments (twice),
  // the normals and the fine level alone pass a million points in all five.
  EXPECT_GE(checks, 5 * 1'000'000 / kItemsPerStopCheck);

  // A check that throws ends the indexing there: the exception is the caller's own. Once stopped,
  // every check throws, as a cancelled job's does: the stages running beside the one that threw
  // end at their own next check.
  for (const std::size_t stop_at : {std::size_t{1}, std::size_t{40}, checks / 2}) {
    std::atomic<std::size_t> calls{0};
    EXPECT_THROW(SceneIndex(scene, SceneSettings{},
                            [&] {
                              if (++calls >= stop_at) throw Stopped{};
                            }),
                 Stopped)
        << "stopping at check " << stop_at;
    EXPECT_LE(calls.load(), stop_at + 64) << "the work went on after the stop";
  }
  // And a search: its stop check is asked during the indexing and between candidates.
  const Landmark cup = load_landmark(LMK_SOURCE_DIR "/tests/cli/fixtures/cup_v2.lmk");
  FindSettings s;
  s.scene.base_frame = true;
  std::atomic<std::size_t> calls{0};
  s.execution.stop = [&] {
    if (++calls >= 100) throw Stopped{};
  };
  EXPECT_THROW(find_landmark(scene, cup, s), Stopped);
}

}  // namespace
}  // namespace lmk
