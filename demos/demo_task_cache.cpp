// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/demos/detail/demo_task_cache.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lmk/demos/detail/demo_tasks_json.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/version.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/find_landmark.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

// What the demo tasks judge: 2 adds the ground-truth contacts of issue #60 (an older result, which
// never checked them, must not count as having none).
constexpr int kJudgeRevision = 3;

// Keyed by everything that decides a task's results: the lmk version and search revision (the
// code), the confidence calibration and cut, the task, and the success criterion. Threads do not
// change results.
fs::path cache_file(const DemoTasksSettings& settings, int task) {
  const ConfidenceCalibration& calibration = builtin_confidence_calibration();
  Fnv1a hash;
  hash.add(kVersion).add_value(kSearchRevision).add_value(kJudgeRevision);
  hash.add_value(settings.min_confidence);
  hash.add_value(settings.look_again).add_value(settings.unseen_looks).add_value(settings.watch);
  hash.add_value(settings.check_collisions).add_value(settings.approach);
  const Pr2MotionCheckSettings& m = settings.motion_check;
  hash.add_value(m.motion.padding)
      .add_value(m.motion.self_padding)
      .add_value(m.motion.planning_time)
      .add_value(m.motion.planning_checks);
  hash.add_value(m.scene.unknown_is_occupied)
      .add_value(m.scene.unseen_is_occupied)
      .add_value(m.self_filter_margin);
  hash.add(calibration.metric).add_value(calibration.bias);
  for (const auto& [name, weight] : calibration.weights) hash.add(name).add_value(weight);
  const std::string key = hash.add_value(task)
                              .add_value(settings.max_position_error)
                              .add_value(settings.max_rotation_error)
                              .hex();
  return fs::path(settings.cache_dir) / "demo-tasks" /
         ("task" + std::to_string(task) + "-" + key + ".json");
}

}  // namespace

std::optional<std::vector<DemoScenarioResult>> read_cached_demo_task(
    const DemoTasksSettings& settings, int task) {
  if (settings.cache_dir.empty()) return std::nullopt;
  const fs::path file = cache_file(settings, task);
  std::error_code ec;
  if (!fs::exists(file, ec)) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_input_file(file.string(), kJsonInput));
    std::vector<DemoScenarioResult> results;
    for (const nlohmann::json& s : j.at("scenarios"))
      results.push_back(detail::scenario_from_json(s));
    if (results.empty()) return std::nullopt;
    for (const DemoScenarioResult& r : results) {
      if (r.task != task) return std::nullopt;
    }
    return results;
  } catch (const std::exception&) {
    return std::nullopt;  // damaged (an interrupted write cannot leave one) or foreign: run again
  }
}

void write_cached_demo_task(const DemoTasksSettings& settings, int task,
                            const std::vector<DemoScenarioResult>& results) {
  if (settings.cache_dir.empty()) return;
  const fs::path file = cache_file(settings, task);
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) {
    throw Error(file.parent_path().string() + ": cannot create the cache directory (" +
                ec.message() + ")");
  }
  nlohmann::json scenarios = nlohmann::json::array();
  for (const DemoScenarioResult& r : results) scenarios.push_back(detail::scenario_to_json(r));
  write_text_atomically(file, nlohmann::json{{"scenarios", scenarios}}.dump(2) + "\n");
}

}  // namespace lmk
