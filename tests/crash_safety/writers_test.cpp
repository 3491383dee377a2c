// SPDX-License-Identifier: BSD-3-Clause
// Crash safety of every file lmk writes (issue #17): each writer is killed with SIGKILL at random
// moments, 50 times; its target then holds the old contents or the new, whole and valid as lmk's
// own reader sees it, and the next write leaves no temporary behind. The writers: point clouds,
// landmarks, programs, datasets, the evaluation's cache entries and reports, and the demo tasks'
// cache entries. All go through write_file_atomically (geometry/atomic_file.h).

#include <gtest/gtest.h>

#include <stdexcept>

#include "lmk/datasets/dataset.h"
#include "lmk/demos/detail/demo_task_cache.h"
#include "lmk/eval/detail/pair_cache.h"
#include "lmk/eval/evaluation_report.h"
#include "lmk/eval/internal/evaluation_json.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/pbd/program.h"
#include "tests/support/kill_loop.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// Which of `versions` equals `value`; throws when none does.
template <typename T>
int which_of(const T& value, const std::array<T, 2>& versions) {
  for (int v : {0, 1}) {
    if (value == versions[v]) return v;
  }
  throw std::runtime_error("the target holds neither version");
}

// A writer is crash safe when every kill left a valid target (old or new) and, once it writes
// again, no temporary is left in `dir`.
void expect_crash_safe_writer(const fs::path& dir, const std::function<void(int)>& write,
                              const std::function<int()>& version_held) {
  test::expect_crash_safe(test::kill_writer_repeatedly(write, version_held));
  write(0);
  EXPECT_EQ(test::temporaries_in(dir), 0u);
  EXPECT_EQ(version_held(), 0);
}

TEST(CrashSafety, PointClouds) {
  test::ScratchDir dir;
  const std::string target = dir.file("scene.pcd");
  const std::array<PointCloud, 2> clouds = {test::random_cloud(20000, 1),
                                            test::random_cloud(30000, 2)};
  const std::array<std::vector<Eigen::Vector3f>, 2> points = {clouds[0].points, clouds[1].points};
  expect_crash_safe_writer(
      dir.path(), [&](int v) { write_cloud(target, clouds[v]); },
      [&] { return which_of(read_cloud(target).points, points); });
}

TEST(CrashSafety, Landmarks) {
  test::ScratchDir dir;
  const std::string target = dir.file("box.lmk");
  PointCloud scene = test::random_cloud(60000, 3, 0.4f);
  scene.T_cloud_sensor.translation() << 0.1, -0.2, -1.5;
  CaptureSettings settings;
  settings.leaf_size = 0.01;
  const Box box(pose_from_xyz_rpy({0.05, 0.0, 0.1}, {0.3, -0.2, 1.0}), {0.2, 0.3, 0.1});
  const std::array<Landmark, 2> landmarks = {capture(scene, box, "old", settings),
                                             capture(scene, box, "new", settings)};
  const std::array<std::string, 2> names = {"old", "new"};
  expect_crash_safe_writer(
      dir.path(), [&](int v) { save_landmark(target, landmarks[v]); },
      [&] { return which_of(load_landmark(target).name, names); });
}

TEST(CrashSafety, Programs) {
  test::ScratchDir dir;
  const std::string target = dir.file("program.json");
  std::array<Program, 2> programs;
  for (int v : {0, 1}) {
    programs[v].name = v ? "new" : "old";
    programs[v].landmarks = {{"rack", "rack.lmk"}};
    for (int k = 0; k < 20 + 30 * v; ++k) {
      ProgramStep step;
      step.right = ArmTarget{"rack", pose_from_xyz_rpy({0.01 * k, 0.05, 0.2}, {0, 1.2, 0}),
                             GripperAction::kOpen};
      programs[v].steps.push_back(step);
    }
  }
  const std::array<std::string, 2> texts = {program_to_json(programs[0]),
                                            program_to_json(programs[1])};
  expect_crash_safe_writer(
      dir.path(), [&](int v) { save_program(target, programs[v]); },
      [&] { return which_of(program_to_json(load_program(target)), texts); });
}

TEST(CrashSafety, Datasets) {
  test::ScratchDir dir;
  test::write_text(dir.file("scene.pcd"), "");  // save_dataset checks that the files exist
  test::write_text(dir.file("box.lmk"), "");
  std::array<Dataset, 2> datasets;
  for (int v : {0, 1}) {
    datasets[v].name = v ? "new" : "old";
    datasets[v].landmarks = {{"box", "box.lmk", Symmetry{}}};
    for (int k = 0; k < 50 + 50 * v; ++k) {
      DatasetScene scene;
      scene.name = "scene " + std::to_string(k);
      scene.file = "scene.pcd";
      scene.setting = "simple";
      scene.pairs = {{"box", true, {pose_from_xyz_rpy({0.1 * k, 0, 1}, {0, 0, 0.1 * k})}, {}, {}}};
      datasets[v].scenes.push_back(scene);
    }
  }
  const std::array<std::string, 2> names = {"old", "new"};
  expect_crash_safe_writer(
      dir.path(), [&](int v) { save_dataset(dir.path().string(), datasets[v]); },
      [&] { return which_of(load_dataset(dir.path().string()).name, names); });
}

// Two results of one pair: the old search found one box, the new one two.
std::array<PairResult, 2> two_results_of_a_pair() {
  std::array<PairResult, 2> results;
  for (int v : {0, 1}) {
    PairResult& r = results[v];
    r.scene = "scene";
    r.landmark = "box";
    r.setting = "simple";
    r.in_context = true;
    r.truth = {pose_from_xyz_rpy({0.5, 0, 1}, {0, 0, 0.3})};
    for (int k = 0; k <= v; ++k) {
      FoundBox found;
      found.box = Box(pose_from_xyz_rpy({0.5 + 0.2 * k, 0, 1}, {0, 0, 0.3}), {0.1, 0.2, 0.3});
      found.error = 0.001 * (k + 1);
      r.found.push_back(found);
    }
    r.seconds = 0.5;
    r.seeds = 100;
  }
  return results;
}

TEST(CrashSafety, EvaluationCacheEntries) {
  test::ScratchDir dir;
  const detail::PairCache cache(dir.path().string(), "key");
  const std::array<PairResult, 2> results = two_results_of_a_pair();
  const std::array<std::size_t, 2> found = {1, 2};
  expect_crash_safe_writer(
      dir.path(), [&](int v) { cache.store(results[v], 0.01, {}); },
      [&] {
        const std::optional<PairResult> entry = cache.read("scene", "box");
        if (!entry) throw std::runtime_error("the cache entry is missing or damaged");
        return which_of(entry->found.size(), found);
      });
}

TEST(CrashSafety, EvaluationReports) {
  test::ScratchDir dir;
  const std::array<PairResult, 2> results = two_results_of_a_pair();
  std::array<Evaluation, 2> evaluations;
  for (int v : {0, 1}) {
    evaluations[v].settings.find = FindSettings().resolved();  // as evaluate() leaves it
    evaluations[v].dataset = v ? "new" : "old";
    evaluations[v].fingerprint = "fingerprint";
    evaluations[v].pairs = {results[v]};
  }
  // The three files of each version, as a complete write leaves them.
  const std::vector<std::string> files = {"report.json", "report.md", "report.html"};
  std::array<std::vector<std::string>, 2> expected;
  for (int v : {0, 1}) {
    const fs::path reference = dir.path() / ("reference" + std::to_string(v));
    write_evaluation_report(reference.string(), evaluations[v]);
    for (const std::string& f : files)
      expected[v].push_back(test::read_bytes((reference / f).string()));
  }
  const fs::path report = dir.path() / "report";
  // Each file is written atomically on its own: a kill between them may leave the new report.json
  // beside the old report.md, but never a file that is neither.
  expect_crash_safe_writer(
      dir.path(), [&](int v) { write_evaluation_report(report.string(), evaluations[v]); },
      [&] {
        int json_version = -1;
        for (std::size_t i = 0; i < files.size(); ++i) {
          const std::string now = test::read_bytes((report / files[i]).string());
          const int v = which_of(now, {expected[0][i], expected[1][i]});
          if (i == 0) json_version = v;
        }
        return json_version;
      });
}

TEST(CrashSafety, DemoTaskCacheEntries) {
  test::ScratchDir dir;
  DemoTasksSettings settings;
  settings.cache_dir = dir.path().string();
  std::array<std::vector<DemoScenarioResult>, 2> results;
  for (int v : {0, 1}) {
    for (int k = 0; k < 3 + 3 * v; ++k) {
      DemoScenarioResult s;
      s.task = 2;
      s.name = "scenario " + std::to_string(k);
      s.success = true;
      s.reason = v ? "new" : "old";
      results[v].push_back(s);
    }
  }
  const std::array<std::size_t, 2> sizes = {3, 6};
  expect_crash_safe_writer(
      dir.path(), [&](int v) { write_cached_demo_task(settings, 2, results[v]); },
      [&] {
        const auto entry = read_cached_demo_task(settings, 2);
        if (!entry) throw std::runtime_error("the cache entry is missing or damaged");
        return which_of(entry->size(), sizes);
      });
}

}  // namespace
}  // namespace lmk
