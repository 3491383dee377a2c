// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/api.h"

#include <malloc.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/version.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/metrics/error_metrics.h"
#include "lmk/serve/api_error.h"
#include "lmk/serve/request_fields.h"

namespace lmk::serve {

Api::Api(ServeSettings settings, const std::filesystem::path& scratch_dir)
    : settings_(std::move(settings)),
      budget_(settings_.memory_budget > 0 ? settings_.memory_budget : default_memory_budget()),
      scenes_(UploadLimits{settings_.max_uploads, settings_.max_upload_points,
                           settings_.max_uploaded_points},
              scratch_dir, budget_, load_depth_correction_if_given(settings_.depth_correction)),
      library_(settings_.landmarks_dir),
      calibration_(settings_.confidence_calibration.empty()
                       ? nullptr
                       : std::make_shared<const ConfidenceCalibration>(
                             read_confidence_calibration(settings_.confidence_calibration))) {
  for (const std::string& path : settings_.scenes) scenes_.add_file(path);
  if (!settings_.programs_dir.empty()) {
    if (!std::filesystem::is_directory(settings_.programs_dir)) {
      throw Error("--programs " + settings_.programs_dir + ": not a directory");
    }
    programs_dir_ = std::filesystem::canonical(settings_.programs_dir);
  }
  JobLimits limits;
  limits.max_queued = settings_.max_queued_jobs;
  limits.abandon_after = settings_.abandon_after;
  jobs_ = std::make_unique<JobPool>(settings_.workers, limits);
}

ApiResponse Api::info() const {
  FindSettings defaults = scene_find_settings();
  return {200,
          {{"version", kVersion},
           {"landmarks_dir", library_.directory().string()},
           {"programs_dir", programs_dir_.string()},
           {"workers", settings_.workers},
           {"max_upload_bytes", settings_.max_upload_bytes},
           {"base_frame", defaults.scene.base_frame},
           {"methods", search_methods()},
           {"metrics", error_metric_names()},
           {"setting_keys", find_setting_keys()},
           {"memory", budget_.to_json()}}};
}

FindSettings Api::scene_find_settings() const {
  FindSettings s;
  s.scene.base_frame = settings_.base_frame;
  s.scene.up = settings_.up;
  s.selection.calibration = calibration_;
  return s;
}

MemoryBudget::Reservation Api::reserve_search(const Scene& scene, const SceneSettings& settings,
                                              const char* kind) {
  return budget_.reserve(scenes_.search_footprint(scene, settings), "jobs",
                         std::string(kind) + " in scene " + scene.id);
}

ApiResponse Api::run_job(const std::string& kind, const nlohmann::json& body,
                         MemoryBudget::Reservation memory, JobPool::Work work) {
  const bool wait = optional_bool(body, "wait", false, kind);
  // The job holds its reservation until it ends, or until it is dropped unrun (cancelled, the
  // queue stopped): the pool frees a job's work then.
  auto held = std::make_shared<MemoryBudget::Reservation>(std::move(memory));
  JobPool::Work priced = [held, work = std::move(work)](JobProgress& progress) {
    // What the job freed goes back to the system before its reservation does, so that the next
    // job admitted finds the memory it was promised (glibc keeps freed pages otherwise).
    struct GiveBack {
      ~GiveBack() { malloc_trim(0); }
    } give_back;
    return work(progress);
  };
  const std::string id = jobs_->submit(kind, std::move(priced));
  if (!wait) return {202, {{"job", id}, {"url", "/api/jobs/" + id}}};
  // Waiting is for scripts: the page polls instead, to show progress.
  const nlohmann::json job = jobs_->status(id, kMaxRequestWait).value();
  if (!JobPool::finished(job)) {
    return {202,
            {{"job", id},
             {"url", "/api/jobs/" + id},
             {"state", job["state"]},
             {"note", "still running (or many requests wait already): poll the url"}}};
  }
  if (job["state"] == "failed") return {job["status"].get<int>(), job};
  return {200, job};
}

ApiResponse Api::cancel_job(const std::string& id) {
  const std::optional<bool> cancelled = jobs_->cancel(id);
  if (!cancelled)
    throw not_found("no job '" + printable(id, kEchoedBytes) +
                    "' (finished jobs are kept for a while only)");
  if (!*cancelled) throw conflict("job '" + printable(id, kEchoedBytes) + "' has finished already");
  return {200, {{"job", id}, {"cancelled", true}}};
}

ApiResponse Api::health() { return {200, {{"ok", true}}}; }

void Api::stop() { jobs_->stop(); }

ApiResponse Api::job(const std::string& id, const std::string& wait) const {
  double seconds = 0.0;
  if (!wait.empty()) {
    try {
      std::size_t used = 0;
      seconds = std::stod(wait, &used);
      if (used != wait.size() || !std::isfinite(seconds) || seconds < 0.0) throw bad_request("");
    } catch (const std::exception&) {
      throw bad_request("job: wait=" + wait + ": must be a number of seconds, at least 0");
    }
    seconds = std::min(seconds, kMaxRequestWait);  // a long poll, not a hung connection
  }
  const auto status = jobs_->status(id, seconds);
  if (!status)
    throw not_found("no job '" + printable(id, kEchoedBytes) +
                    "' (finished jobs are kept for a while only)");
  return {200, *status};
}

}  // namespace lmk::serve
