// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/job_pool.h"

#include <chrono>
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {

struct JobPool::Job {
  Job(const JobPool& pool, double submitted)
      : progress([&pool, this] { pool.go_on(*this); }), last_asked(submitted) {}
  std::atomic<bool> cancelled{false}, abandoned{false};
  std::string id, kind;
  Work work;
  std::string state = "queued";
  JobProgress progress;
  nlohmann::json result;
  std::string error;
  int status = 200;
  nlohmann::json details;  // an ApiError's, beside its message
  Stopwatch running;       // restarted when the job starts
  double seconds = 0.0;
  // When a request last asked about the job (JobPool::now()), and how many ask at the moment.
  std::atomic<double> last_asked;
  std::atomic<int> askers{0};
};

namespace {

// A job's state says it has ended: it has its result or its error.
bool has_ended(const std::string& state) { return state == "done" || state == "failed"; }

}  // namespace

void JobProgress::report(double fraction, std::string message) {
  go_on_();
  std::lock_guard<std::mutex> lock(mutex_);
  fraction_ = fraction;
  message_ = std::move(message);
}

nlohmann::json JobProgress::to_json() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {{"fraction", fraction_}, {"message", message_}};
}

JobPool::JobPool(int workers, JobLimits limits) : limits_(std::move(limits)) {
  for (int i = 0; i < std::max(1, workers); ++i) workers_.emplace_back([this] { work_loop(); });
}

JobPool::~JobPool() {
  stop();
  for (std::thread& t : workers_) t.join();
}

double JobPool::now() const {
  if (limits_.clock) return limits_.clock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string JobPool::abandoned_message() const {
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%g", limits_.abandon_after);
  return std::string("abandoned: nobody asked about the job for ") + seconds +
         " s (poll GET /api/jobs/ID to keep a job running)";
}

bool JobPool::abandoned(Job& job) const {
  if (job.askers > 0 || !(now() - job.last_asked > limits_.abandon_after)) return false;
  job.abandoned = true;
  job.cancelled = true;
  return true;
}

void JobPool::go_on(Job& job) const {
  if (stopping_) throw JobCancelled("the server is stopping");
  if (job.cancelled || abandoned(job)) {
    throw JobCancelled(job.abandoned ? abandoned_message() : "cancelled (DELETE /api/jobs/ID)");
  }
}

void JobPool::asking(Job& job, int change) const {
  job.askers += change;
  job.last_asked = now();
}

void JobPool::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    for (const auto& job : queue_) finish(*job, {}, "the server is stopping", 503);
    queue_.clear();
  }
  changed_.notify_all();
}

bool JobPool::ended_within(double seconds) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, std::chrono::duration<double>(seconds),
                           [this] { return running_ == 0; });
}

std::optional<bool> JobPool::cancel(const std::string& id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  Job& job = *it->second;
  if (has_ended(job.state)) return false;
  job.cancelled = true;  // a running job ends at its next progress report
  if (job.state == "queued") {
    for (auto q = queue_.begin(); q != queue_.end(); ++q) {
      if ((*q)->id == id) {
        queue_.erase(q);
        break;
      }
    }
    finish(job, {}, "cancelled (DELETE /api/jobs/ID)", 409);
  }
  return true;
}

bool JobPool::finished(const nlohmann::json& status) {
  return has_ended(status.value("state", ""));
}

std::string JobPool::submit(const std::string& kind, Work work) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (queue_.size() >= limits_.max_queued) {
    ApiError busy(503, "busy: " + std::to_string(queue_.size()) +
                           " jobs are waiting; try again when some have finished");
    busy.set_retry_after(kRetryAfterSeconds);
    throw busy;
  }
  auto job = std::make_shared<Job>(*this, now());
  job->id = "job-" + std::to_string(next_id_++);
  job->kind = kind;
  job->work = std::move(work);
  jobs_[job->id] = job;
  queue_.push_back(job);
  changed_.notify_all();
  return job->id;
}

void JobPool::work_loop() {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = queue_.front();
      queue_.pop_front();
      if (abandoned(*job)) {  // its client went away while it waited
        finish(*job, {}, abandoned_message(), 409);
        continue;
      }
      job->state = "running";
      job->running.restart();
      ++running_;
    }
    nlohmann::json result;
    std::string error;
    int status = 200;
    nlohmann::json details;
    // A job's failure is its own: it is reported on the job and never leaves the worker.
    try {
      result = job->work(job->progress);
    } catch (const JobCancelled& e) {
      error = e.what();
      status = job->cancelled ? 409 : 503;
    } catch (const ApiError& e) {
      error = e.what();
      status = e.status();
      details = e.details();
    } catch (const Error& e) {
      error = e.what();
      status = 422;
    } catch (const std::exception& e) {
      error = std::string("internal error: ") + e.what();
      status = 500;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    --running_;
    job->seconds = job->running.seconds();
    finish(*job, std::move(result), std::move(error), status, std::move(details));
  }
}

// Called with mutex_ held.
void JobPool::finish(Job& job, nlohmann::json result, std::string error, int status,
                     nlohmann::json details) {
  job.state = error.empty() ? "done" : "failed";
  job.result = std::move(result);
  job.error = std::move(error);
  job.status = status;
  job.details = std::move(details);
  job.work = nullptr;  // frees what the work held (scenes, landmarks)
  finished_.push_back(job.id);
  while (finished_.size() > limits_.max_kept) {
    jobs_.erase(finished_.front());
    finished_.pop_front();
  }
  changed_.notify_all();
}

nlohmann::json JobPool::describe(const Job& job) const {
  nlohmann::json j = {{"id", job.id},
                      {"kind", job.kind},
                      {"state", job.state},
                      {"progress", job.progress.to_json()}};
  if (job.state == "done") {
    j["result"] = job.result;
    j["seconds"] = job.seconds;
  } else if (job.state == "failed") {
    if (job.details.is_object()) j.update(job.details);
    j["error"] = job.error;
    j["status"] = job.status;
  } else if (job.state == "queued") {
    std::size_t ahead = 0;
    for (const auto& q : queue_) {
      if (q->id == job.id) break;
      ++ahead;
    }
    j["queue_position"] = ahead;
  }
  return j;
}

std::optional<nlohmann::json> JobPool::status(const std::string& id, double wait_seconds) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  const std::shared_ptr<Job> job = it->second;
  const auto done = [this, &job] { return stopping_ || has_ended(job->state); };
  asking(*job, +1);
  if (wait_seconds > 0.0 && waiters_ < limits_.max_waiters) {
    ++waiters_;
    changed_.wait_for(lock, std::chrono::duration<double>(wait_seconds), done);
    --waiters_;
  }
  asking(*job, -1);
  return describe(*job);
}

nlohmann::json JobPool::wait(const std::string& id) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) throw not_found("no job '" + printable(id, kEchoedBytes) + "'");
  const std::shared_ptr<Job> job = it->second;
  asking(*job, +1);
  changed_.wait(lock, [this, &job] { return stopping_ || has_ended(job->state); });
  asking(*job, -1);
  return describe(*job);
}

}  // namespace lmk::serve
