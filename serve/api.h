// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON API of `lmk serve`, apart from HTTP so that each endpoint is one method (docs/serve.md
// lists them). The page uses nothing else, and scripts can drive it the same way. Bad requests
// throw ApiError with their status; nothing a request does can stop the server.
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lmk/search/find_settings.h"
#include "lmk/search/landmark_library.h"
#include "lmk/serve/cloud_download.h"
#include "lmk/serve/job_pool.h"
#include "lmk/serve/memory_budget.h"
#include "lmk/serve/scene_store.h"
#include "lmk/serve/serve_settings.h"

namespace lmk::serve {

struct ApiResponse {
  int status = 200;
  nlohmann::json body;
};

/// The longest a request waits for a job, s: a POST with "wait": true, or a long poll
/// (GET /api/jobs/ID?wait=S). Waiting requests hold HTTP threads; past it the client polls.
inline constexpr double kMaxRequestWait = 10.0;

class Api {
 public:
  /// Reads every scene and opens the landmark directory; lmk::Error for a bad scene file or
  /// directory. Uploads are parsed in `scratch_dir`.
  Api(ServeSettings settings, const std::filesystem::path& scratch_dir);

  const ServeSettings& settings() const { return settings_; }
  /// What the server's work may take: the HTTP layer reserves a JSON body's parse in it before the
  /// body is read.
  MemoryBudget& budget() { return budget_; }

  // GET /api/info
  ApiResponse info() const;
  // Scenes (api_scenes.cpp): GET /api/scenes, POST /api/scenes?name=F, GET /api/scenes/ID,
  // GET /api/scenes/ID/cloud?max_points=N
  ApiResponse scenes() const;
  ApiResponse upload_scene(const std::string& name, const std::string& bytes);
  /// An upload written to a scratch file as it arrived (new_upload_file).
  ApiResponse upload_scene(UploadFile& file);
  std::unique_ptr<UploadFile> new_upload_file(const std::string& name) const {
    return scenes_.new_upload_file(name);
  }
  ApiResponse scene(const std::string& id) const;
  /// The scene's points, written a piece at a time (ApiError for a bad id or max_points).
  CloudDownload scene_cloud(const std::string& id, const std::string& max_points) const;
  // Capture (api_capture.cpp): POST /api/guess, POST /api/check, GET /api/landmarks,
  // GET /api/landmarks/NAME, POST /api/landmarks
  ApiResponse guess(const std::string& body) const;
  ApiResponse check(const std::string& body);
  ApiResponse landmarks() const;
  ApiResponse landmark(const std::string& name) const;
  ApiResponse save_landmark(const std::string& body);
  // Searches (api_find.cpp): POST /api/find, GET /api/jobs/ID?wait=S, DELETE /api/jobs/ID
  ApiResponse find(const std::string& body);
  ApiResponse job(const std::string& id, const std::string& wait) const;
  ApiResponse cancel_job(const std::string& id);
  // GET /api/health: answers at once, whatever the jobs are doing.
  static ApiResponse health();
  /// Stops the jobs and wakes every request waiting for one (the server is stopping).
  void stop();
  /// After stop(): whether the jobs under way have ended within `seconds` (JobPool::ended_within).
  bool jobs_ended_within(double seconds) const { return jobs_->ended_within(seconds); }
  // Programs (api_programs.cpp): GET /api/programs, GET /api/programs/NAME,
  // POST /api/programs/NAME/plan
  ApiResponse programs() const;
  ApiResponse program(const std::string& name) const;
  ApiResponse plan(const std::string& name, const std::string& body);

 private:
  /// The search settings a scene starts from: its up axis as the server was told.
  FindSettings scene_find_settings() const;
  /// Queues `work`; with body["wait"] true, waits for it up to kMaxRequestWait and answers with
  /// the finished job (200), otherwise (or when it is still running then, or too many requests
  /// wait already) answers 202 with the job's id and where to poll it.
  ApiResponse run_job(const std::string& kind, const nlohmann::json& body,
                      MemoryBudget::Reservation memory, JobPool::Work work);
  /// The memory a job of `kind` that indexes `scene` with `settings` and searches it takes,
  /// reserved (ApiError 503 or 413 when it does not fit).
  MemoryBudget::Reservation reserve_search(const Scene& scene, const SceneSettings& settings,
                                           const char* kind);
  /// The program file `name` (NAME.json in the programs directory); ApiError 400/403/404.
  std::filesystem::path program_path(const std::string& name) const;

  ServeSettings settings_;
  MemoryBudget budget_;  // before what holds its reservations: destroyed after them
  SceneStore scenes_;
  LandmarkLibrary library_;
  /// settings_.confidence_calibration, read once; null: the built-in one.
  std::shared_ptr<const ConfidenceCalibration> calibration_;
  std::filesystem::path programs_dir_;  ///< canonical; empty: none
  // Last: destroyed first, so that no job outlives what it uses.
  std::unique_ptr<JobPool> jobs_;
};

}  // namespace lmk::serve
