// SPDX-License-Identifier: BSD-3-Clause
// lmk serve's worker pool: results and failures kept per job, the queue's bound, and a shutdown
// that ends the jobs under way instead of waiting for them.
#include "lmk/serve/job_pool.h"

#include <gtest/gtest.h>

#include <atomic>
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

}  // namespace
}  // namespace lmk::serve
