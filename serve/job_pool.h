// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The worker pool of `lmk serve`: searches, distinctiveness checks and plans run here, a few at a
// time, so that the HTTP threads stay free to answer the page while they run. Each job reports
// its progress, and its result (or error) stays readable by id until newer jobs push it out.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace lmk::serve {

/// Thrown by JobProgress::report when the pool is stopping or the job was cancelled: the job ends
/// there.
struct JobCancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a running job tells its watchers. Safe from any thread, as search progress callbacks are.
class JobProgress {
 public:
  JobProgress(const std::atomic<bool>& stopping, const std::atomic<bool>& cancelled)
      : stopping_(stopping), cancelled_(cancelled) {}
  /// Records the progress; throws JobCancelled once the pool is stopping or the job is cancelled,
  /// so that a long search ends at its next seed instead of holding the server's shutdown.
  void report(double fraction, std::string message);
  nlohmann::json to_json() const;

 private:
  const std::atomic<bool>& stopping_;
  const std::atomic<bool>& cancelled_;
  mutable std::mutex mutex_;
  double fraction_ = 0.0;
  std::string message_;
};

class JobPool {
 public:
  /// The job's work: its result, or it throws (ApiError keeps its status; lmk::Error is 422).
  using Work = std::function<nlohmann::json(JobProgress&)>;

  /// `workers` threads; at most `max_queued` jobs waiting; the last `max_kept` finished jobs kept;
  /// at most `max_waiters` requests waiting for jobs at once (the rest are answered at once, so
  /// that waiting requests never hold every HTTP thread).
  JobPool(int workers, std::size_t max_queued, std::size_t max_kept = 256,
          std::size_t max_waiters = 8);
  /// stop(), then waits for the workers.
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  /// Queues `work` as a job of `kind` ("find", "check", "plan"); its id. ApiError 503 when the
  /// queue is full.
  std::string submit(const std::string& kind, Work work);
  /// The job's state as JSON: {id, kind, state: queued|running|done|failed, progress, result or
  /// error and status}, after waiting up to `wait_seconds` for it to finish (not at all when
  /// max_waiters requests wait already, or once the pool stops). nullopt: no such job.
  std::optional<nlohmann::json> status(const std::string& id, double wait_seconds = 0.0) const;
  /// The job's state once it has finished, or once the pool stops; no limit on the time or on the
  /// waiters (for callers that own the pool, such as tests; requests use status()).
  nlohmann::json wait(const std::string& id) const;
  /// Whether a status() says the job has ended (done or failed).
  static bool finished(const nlohmann::json& status);
  /// Cancels a job: a queued one never runs, a running one ends at its next progress report; both
  /// end failed with status 409. nullopt: no such job; false: it had finished already.
  std::optional<bool> cancel(const std::string& id);
  /// Stops the jobs under way at their next progress report, drops those still queued, and wakes
  /// every request waiting for one: the server then stops at once (Ctrl-C).
  void stop();

 private:
  struct Job;
  void work_loop();
  nlohmann::json describe(const Job& job) const;
  void finish(Job& job, nlohmann::json result, std::string error, int status);

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::string> finished_;
  std::size_t max_queued_, max_kept_, max_waiters_;
  mutable std::size_t waiters_ = 0;
  std::size_t next_id_ = 1;
  std::atomic<bool> stopping_{false};
  std::vector<std::thread> workers_;
};

}  // namespace lmk::serve
