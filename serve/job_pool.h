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

#include "lmk/geometry/stop_check.h"

namespace lmk::serve {

/// Thrown by JobProgress::report when the pool is stopping or the job was cancelled: the job ends
/// there.
struct JobCancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a running job tells its watchers. Safe from any thread, as search progress callbacks are.
class JobProgress {
 public:
  /// `go_on` throws JobCancelled when the job must end: the pool stops, or the job was cancelled
  /// or abandoned.
  explicit JobProgress(std::function<void()> go_on) : go_on_(std::move(go_on)) {}
  /// Records the progress; throws JobCancelled once the pool is stopping or the job is cancelled
  /// or abandoned, so that a long search ends at its next seed instead of holding the server's
  /// shutdown, or a worker that nobody waits for.
  void report(double fraction, std::string message);
  /// Throws JobCancelled as report() does, reporting nothing: what a long stage calls between
  /// pieces of its work (FindSettings::execution.stop), so that a cancelled job ends within
  /// about 200 ms, indexing included.
  void check() const { go_on_(); }
  /// check() as a search's stop check.
  StopCheck stop_check() {
    return [this] { check(); };
  }
  nlohmann::json to_json() const;

 private:
  std::function<void()> go_on_;
  mutable std::mutex mutex_;
  double fraction_ = 0.0;
  std::string message_;
};

/// What the pool's jobs and the requests about them may take.
struct JobLimits {
  std::size_t max_queued = 64;  ///< jobs waiting for a worker; beyond, submit() is 503
  std::size_t max_kept = 256;   ///< finished jobs kept readable; the oldest go first
  /// Requests waiting for jobs at once; the rest are answered at once, so that waiting requests
  /// never hold every HTTP thread.
  std::size_t max_waiters = 8;
  /// s: a job that nobody has asked about (status() or wait()) for this long is cancelled at its
  /// next progress report, or before it starts: its client went away, and it would hold a worker
  /// for nothing (issue #34, finding 3). A waiting request asks for its whole wait.
  double abandon_after = 60.0;
  /// The clock abandon_after is measured on, s; empty: std::chrono::steady_clock. Tests drive
  /// their own.
  std::function<double()> clock;
};

class JobPool {
 public:
  /// The job's work: its result, or it throws (ApiError keeps its status and details;
  /// lmk::Error is 422).
  using Work = std::function<nlohmann::json(JobProgress&)>;

  /// `workers` threads, within `limits`.
  JobPool(int workers, JobLimits limits);
  JobPool(int workers, std::size_t max_queued, std::size_t max_kept = 256,
          std::size_t max_waiters = 8)
      : JobPool(workers, limits_of(max_queued, max_kept, max_waiters)) {}
  /// stop(), then waits for the workers.
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  /// Queues `work` as a job of `kind` ("find", "check", "plan"); its id. ApiError 503 when the
  /// queue is full.
  std::string submit(const std::string& kind, Work work);
  /// The job's state as JSON: {id, kind, state: queued|running|done|failed, progress, result or
  /// error and status (and an ApiError's details)}, after waiting up to `wait_seconds` for it to
  /// finish (not at all when max_waiters requests wait already, or once the pool stops). nullopt:
  /// no such job.
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
  /// After stop(): whether every job under way has ended within `seconds`. A job reports between
  /// seeds, not inside every stage (indexing a 5-million-point scene takes 15 s without a report),
  /// so a caller that must stop in time asks this and leaves the rest behind.
  bool ended_within(double seconds) const;

 private:
  struct Job;
  static JobLimits limits_of(std::size_t max_queued, std::size_t max_kept,
                             std::size_t max_waiters) {
    JobLimits l;
    l.max_queued = max_queued;
    l.max_kept = max_kept;
    l.max_waiters = max_waiters;
    return l;
  }
  void work_loop();
  double now() const;
  // Throws JobCancelled when `job` must end: the pool stops, or it was cancelled or abandoned.
  void go_on(Job& job) const;
  std::string abandoned_message() const;
  // Whether nobody has asked about `job` for limits_.abandon_after; then it is cancelled.
  bool abandoned(Job& job) const;
  // A request asks about `job` from now (+1) or has stopped asking (-1); called with mutex_ held.
  void asking(Job& job, int change) const;
  nlohmann::json describe(const Job& job) const;
  void finish(Job& job, nlohmann::json result, std::string error, int status,
              nlohmann::json details = nullptr);

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::string> finished_;
  JobLimits limits_;
  mutable std::size_t waiters_ = 0;
  std::size_t running_ = 0;  // jobs a worker runs at the moment
  std::size_t next_id_ = 1;
  std::atomic<bool> stopping_{false};
  std::vector<std::thread> workers_;
};

}  // namespace lmk::serve
