// SPDX-License-Identifier: BSD-3-Clause
// lmk serve's worker pool: results and failures kept per job, the queue's bound, and a shutdown
// that ends the jobs under way instead of waiting for them.
#include "lmk/serve/job_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <future>
#include <mutex>
#include <optional>
#include <thread>

#include "lmk/geometry/error.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {
namespace {

TEST(JobPool, KeepsEachJobsResultOrItsErrorWithItsStatus) {
  JobPool pool(2, 8);
  const std::string ok = pool.submit("find", [](JobProgress& p) {
    p.report(0.5, "half");
    return nlohmann::json{{"answer", 42}};
  });
  const std::string missing =
      pool.submit("find", [](JobProgress&) -> nlohmann::json { throw not_found("no landmark"); });
  const std::string refused =
      pool.submit("check", [](JobProgress&) -> nlohmann::json { throw Error("too flat"); });
  const std::string broken =
      pool.submit("plan", [](JobProgress&) -> nlohmann::json { throw std::runtime_error("bug"); });

  const nlohmann::json done = pool.wait(ok);
  EXPECT_EQ(done["state"], "done");
  EXPECT_EQ(done["kind"], "find");
  EXPECT_EQ(done["result"]["answer"], 42);
  EXPECT_EQ(done["progress"]["message"], "half");
  EXPECT_EQ(pool.wait(missing)["status"], 404);
  EXPECT_EQ(pool.wait(refused)["status"], 422);
  EXPECT_EQ(pool.wait(refused)["error"], "too flat");
  EXPECT_EQ(pool.wait(broken)["status"], 500);
  EXPECT_FALSE(pool.status("job-999"));
}

TEST(JobPool, AFullQueueIsRefusedAndOldJobsMakeRoomForNewOnes) {
  std::atomic<bool> release{false};
  JobPool pool(1, 2, 3);
  const auto blocking = [&release](JobProgress&) {
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return nlohmann::json();
  };
  const std::string first = pool.submit("find", blocking);
  while ((*pool.status(first))["state"] != "running") std::this_thread::yield();
  pool.submit("find", blocking);
  const std::string third = pool.submit("find", blocking);
  EXPECT_EQ((*pool.status(third))["queue_position"], 1);
  try {
    pool.submit("find", blocking);
    ADD_FAILURE() << "a fourth job fitted in a queue of two";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status(), 503);
  }
  release = true;
  pool.wait(third);
  // Three finished jobs are kept; a fourth pushes the oldest out.
  pool.wait(pool.submit("find", [](JobProgress&) { return nlohmann::json(); }));
  EXPECT_FALSE(pool.status(first));
  EXPECT_TRUE(pool.status(third));
}

TEST(JobPool, StoppingEndsAJobUnderWayAtItsNextReport) {
  std::atomic<bool> started{false}, cancelled{false};
  {
    JobPool pool(1, 2);
    pool.submit("find", [&](JobProgress& p) {
      started = true;
      try {
        for (;;) p.report(0.0, "forever");  // a search that would never end by itself
      } catch (const JobCancelled&) {
        cancelled = true;
        throw;
      }
      return nlohmann::json();
    });
    while (!started) std::this_thread::yield();
  }  // the destructor returns: the job saw the stop
  EXPECT_TRUE(cancelled);
}

// A job that runs until it is cancelled or the pool stops, reporting progress all along.
JobPool::Work forever(std::atomic<bool>& started) {
  return [&started](JobProgress& p) {
    started = true;
    for (;;) p.report(0.0, "forever");
    return nlohmann::json();
  };
}

// Issue #34, finding 3: DELETE /api/jobs/ID.
TEST(JobPool, ACancelledJobEndsAtItsNextReportAndAQueuedOneNeverRuns) {
  std::atomic<bool> started{false}, ran{false};
  JobPool pool(1, 4);
  const std::string running = pool.submit("find", forever(started));
  while (!started) std::this_thread::yield();
  const std::string queued = pool.submit("find", [&ran](JobProgress&) {
    ran = true;
    return nlohmann::json();
  });
  EXPECT_EQ(pool.cancel(queued), std::optional<bool>(true));
  EXPECT_EQ(pool.cancel(running), std::optional<bool>(true));
  const nlohmann::json a = pool.wait(running), b = pool.wait(queued);
  EXPECT_EQ(a["state"], "failed");
  EXPECT_EQ(a["status"], 409);
  EXPECT_EQ(b["status"], 409);
  EXPECT_NE(b["error"].get<std::string>().find("cancelled"), std::string::npos);
  EXPECT_FALSE(ran);
  EXPECT_EQ(pool.cancel(running), std::optional<bool>(false));  // finished already
  EXPECT_EQ(pool.cancel("job-999"), std::nullopt);
}

// Waiting requests hold HTTP threads: past max_waiters a request is answered at once, and stop()
// wakes every one that waits, so that Ctrl-C is not held by a long poll.
TEST(JobPool, WaitersAreBoundedAndWokenWhenThePoolStops) {
  std::atomic<bool> started{false};
  JobPool pool(1, 4, 256, /*max_waiters=*/1);
  const std::string id = pool.submit("find", forever(started));
  while (!started) std::this_thread::yield();
  auto first = std::async(std::launch::async, [&] { return *pool.status(id, 600.0); });
  auto second = std::async(std::launch::async, [&] { return *pool.status(id, 600.0); });
  // One of the two found the only waiting place taken and is answered while the job runs.
  for (;;) {
    if (first.wait_for(std::chrono::milliseconds(0)) == std::future_status::ready) break;
    if (second.wait_for(std::chrono::milliseconds(0)) == std::future_status::ready) {
      std::swap(first, second);
      break;
    }
    std::this_thread::yield();
  }
  EXPECT_EQ(first.get()["state"], "running");
  pool.stop();  // the other waiter returns now, not after 600 s
  const nlohmann::json last = second.get();
  // Woken by the stop: the job still running, or already ended by it at its next report.
  EXPECT_TRUE(last["state"] == "running" || (last["state"] == "failed" && last["status"] == 503))
      << last.dump();
}

// A job that reports once each time the test lets it, so that the test knows when it reported.
class Steps {
 public:
  // Lets the job report once and waits until it has (or has ended).
  void step() {
    std::unique_lock<std::mutex> lock(mutex_);
    ++allowed_;
    changed_.notify_all();
    changed_.wait(lock, [this] { return taken_ == allowed_ || ended_; });
  }
  JobPool::Work work() {
    return [this](JobProgress& p) {
      try {
        for (;;) {
          {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [this] { return allowed_ > taken_; });
          }
          p.report(0.5, "step");
          std::lock_guard<std::mutex> lock(mutex_);
          ++taken_;
          changed_.notify_all();
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        ended_ = true;
        changed_.notify_all();
        throw;
      }
      return nlohmann::json();
    };
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int allowed_ = 0, taken_ = 0;
  bool ended_ = false;
};

// Issue #34, finding 3: a job whose client went away is cancelled after abandon_after, measured
// from the last request about it; the test drives the pool's clock, never the wall's.
// Limits that abandon a job after 60 s of the clock `t`, which the test drives.
JobLimits abandoning_after_a_minute(const std::atomic<double>& t) {
  JobLimits limits;
  limits.abandon_after = 60.0;
  limits.clock = [&t] { return t.load(); };
  return limits;
}

TEST(JobPool, AJobNobodyAsksAboutIsCancelledAndOneAskedAboutRunsOn) {
  std::atomic<double> t{0.0};
  JobPool pool(1, abandoning_after_a_minute(t));
  Steps steps;
  const std::string id = pool.submit("find", steps.work());
  for (double now : {50.0, 100.0, 150.0}) {  // asked about every 50 s: runs on
    t = now;
    steps.step();
    EXPECT_EQ((*pool.status(id))["state"], "running");
  }
  t = 150.0 + 59.0;
  steps.step();  // 59 s unasked: still runs
  t = 150.0 + 61.0;
  steps.step();  // 61 s: ends at this report
  const nlohmann::json ended = pool.wait(id);
  EXPECT_EQ(ended["state"], "failed");
  EXPECT_EQ(ended["status"], 409);
  EXPECT_NE(ended["error"].get<std::string>().find("nobody asked about the job for 60 s"),
            std::string::npos)
      << ended.dump();
}

TEST(JobPool, AQueuedJobNobodyAsksAboutNeverRuns) {
  std::atomic<double> t{0.0};
  JobPool pool(1, abandoning_after_a_minute(t));
  Steps steps;
  const std::string busy = pool.submit("find", steps.work());
  std::atomic<bool> ran{false};
  const std::string forgotten = pool.submit("find", [&ran](JobProgress&) {
    ran = true;
    return nlohmann::json();
  });
  steps.step();  // the first job runs, the second waits behind it
  t = 100.0;
  EXPECT_EQ(pool.cancel(busy), std::optional<bool>(true));
  steps.step();  // the first ends at its report; the worker takes the next
  // A third job, asked about, runs after the forgotten one was dealt with.
  const nlohmann::json third = pool.wait(pool.submit("find", [](JobProgress&) {
    return nlohmann::json{{"ran", true}};
  }));
  EXPECT_EQ(third["state"], "done");
  const nlohmann::json status = *pool.status(forgotten);
  EXPECT_EQ(status["state"], "failed");
  EXPECT_EQ(status["status"], 409);
  EXPECT_FALSE(ran);
}

// A refusal's details (a capture's verdict) stay with the failed job beside its message.
TEST(JobPool, AnApiErrorsDetailsAreKeptWithTheJob) {
  JobPool pool(1, 2);
  const nlohmann::json failed =
      pool.wait(pool.submit("capture", [](JobProgress&) -> nlohmann::json {
        throw ApiError(409, "not distinctive", {{"verdict", {{"distinctive", false}}}});
      }));
  EXPECT_EQ(failed["status"], 409);
  EXPECT_EQ(failed["error"], "not distinctive");
  EXPECT_EQ(failed["verdict"]["distinctive"], false);
}

// Ctrl-C (issue #34, finding 3): a stage without progress reports cannot be stopped, so lmk serve
// asks whether the jobs ended in time and leaves the rest behind.
TEST(JobPool, EndedWithinSaysWhetherAJobWithoutReportsStillRuns) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  JobPool pool(1, 2);
  const std::string id = pool.submit("find", [&started, released](JobProgress&) {
    started = true;
    released.wait();  // a stage that reports nothing until it ends
    return nlohmann::json();
  });
  while (!started) std::this_thread::yield();
  pool.stop();
  EXPECT_FALSE(pool.ended_within(0.0));
  release.set_value();
  EXPECT_TRUE(pool.ended_within(600.0));  // returns as soon as the job has ended
  EXPECT_EQ((*pool.status(id))["state"], "done");
}

}  // namespace
}  // namespace lmk::serve
