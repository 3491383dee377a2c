// SPDX-License-Identifier: BSD-3-Clause
// POST /api/find: landmarks searched in a scene on the worker pool, the scene indexed once for
// all of them (search/scene_index.h), with per-seed progress.
#include <algorithm>

#include "lmk/geometry/error.h"
#include "lmk/json/pose_json.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/internal/find_result_json.h"
#include "lmk/search/internal/find_settings_json.h"
#include "lmk/serve/api.h"
#include "lmk/serve/api_error.h"
#include "lmk/serve/request_fields.h"

namespace lmk::serve {

ApiResponse Api::find(const std::string& body_text) {
  const nlohmann::json body = parse_body(body_text, "find");
  const Scene scene = scenes_.get(required_string(body, "scene", "find"));
  // No more names than the library holds landmarks: each names a different one.
  const std::vector<std::string> all = library_.names();
  const std::vector<std::string> names =
      optional_names(body, "landmarks", all, "find", std::max<std::size_t>(all.size(), 1));
  if (names.empty()) {
    throw bad_request("find: no landmark to search: capture one or name them in 'landmarks'");
  }
  // Everything the search needs is read and checked now: a bad request fails here, not in a job.
  FindSettings settings = scene_find_settings();
  apply_find_settings(body, "find", settings);
  // Each landmark prepared once for searches like this one, and kept in the library for the next.
  std::vector<std::shared_ptr<const LandmarkIndex>> landmarks;
  for (const std::string& name : names) {
    if (!library_.contains(checked_name(name, "find")))
      throw not_found("find: no landmark '" + printable(name, kEchoedBytes) + "'");
    landmarks.push_back(library_.index(name, settings));
  }
  const bool with_rejected = optional_bool(body, "rejected", false, "find");

  // One index of the scene serves every landmark, searched one after another: one search's peak.
  MemoryBudget::Reservation memory = reserve_search(scene, settings.scene, "find");
  return run_job("find", body, std::move(memory), [=](JobProgress& progress) {
    progress.report(0.0, "indexing scene " + scene.name);
    const SceneIndex index(*scene.cloud, settings.scene, progress.stop_check());
    nlohmann::json results = nlohmann::json::array();
    const double n = static_cast<double>(landmarks.size());
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const std::string& name = names[i];
      FindSettings run = settings;
      run.execution.stop = progress.stop_check();
      run.execution.progress = [&progress, &name, i, n](std::size_t done, std::size_t total) {
        const double part = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1;
        progress.report(
            (static_cast<double>(i) + part) / n,
            name + ": " + std::to_string(done) + " of " + std::to_string(total) + " seeds");
      };
      const FindResult found = find_landmark(index, *landmarks[i], run);
      nlohmann::json r = detail::find_result_to_json(found, with_rejected);
      r["landmark"] = name;
      r["box_size"] =
          detail::vector_to_json(landmarks[i]->landmark().box.size);  // every match's box size
      results.push_back(r);
    }
    progress.report(1.0, "done");
    return nlohmann::json{{"scene", scene.id},
                          {"scene_name", scene.name},
                          {"settings", detail::find_settings_to_json(settings)},
                          {"results", results}};
  });
}

}  // namespace lmk::serve
