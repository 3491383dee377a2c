// SPDX-License-Identifier: BSD-3-Clause
// The paper's six PbD tasks end to end on the simulated PR2, and the pieces they stand on: the
// demo world's ground truth and head pointing.

#include "lmk/demos/demo_tasks.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "lmk/demos/demo_world.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/pr2/head_pointing.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

TEST(HeadPointing, PutsTheTargetOnTheOpticalAxis) {
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.2);
  for (const Eigen::Vector3d& target :
       {Eigen::Vector3d(0.8, 0.0, 0.7), Eigen::Vector3d(0.6, 0.4, 0.1),
        Eigen::Vector3d(1.5, -0.8, 1.2)}) {
    const std::vector<double> q = head_joints_looking_at(kinematics, target);
    Eigen::Isometry3d T_base_camera;
    ASSERT_TRUE(kinematics.forward("head", q, T_base_camera).ok());
    const Eigen::Vector3d axis = T_base_camera.linear().col(2);  // optical z: forward
    const Eigen::Vector3d to_target = (target - T_base_camera.translation()).normalized();
    EXPECT_GT(axis.dot(to_target), std::cos(0.5 * M_PI / 180.0)) << target.transpose();
  }
}

TEST(DemoWorld, GroundTruthFollowsObjectsAndHidesNestedOnes) {
  DemoWorld w;
  const Eigen::Isometry3d T = pose_from_xyz_rpy({0.7, 0.1, 0.4}, {0, 0, 0.3});
  w.add("lower", make_bowl(), T, {{"bowl_rim", "rim"}});
  w.add("upper", make_bowl(), T * pose_from_xyz_rpy({0, 0, 0.018}, {0, 0, 0}),
        {{"bowl_rim", "rim"}});
  w.hide_under("lower", "upper");
  auto rims = w.instances("bowl_rim");
  ASSERT_EQ(rims.size(), 1u);
  EXPECT_EQ(rims[0].second, "upper");
  EXPECT_TRUE(rims[0].first.pose.isApprox(
      T * pose_from_xyz_rpy({0, 0, 0.018}, {0, 0, 0}) * make_bowl().part("rim").box.pose, 1e-12));
  w.remove("upper");  // picked: the lower rim shows
  rims = w.instances("bowl_rim");
  ASSERT_EQ(rims.size(), 1u);
  EXPECT_EQ(rims[0].second, "lower");
  EXPECT_THROW(w.remove("upper"), Error);
  EXPECT_THROW(w.add("lower", make_cup(), T), Error);                     // the id is taken
  EXPECT_THROW(w.add("cup", make_cup(), T, {{"cup", "handle"}}), Error);  // no such part
}

TEST(DemoWorld, AFreePatchIsLevelledOntoFreeTableAndNotOntoObjects) {
  DemoWorld w;
  const double top = 0.7;
  w.add("table", make_table({1.0, 1.0, top}), pose_from_xyz_rpy({0.8, 0, 0}, {0, 0, 0}));
  w.add_free_surface(
      {"patch", Box(pose_from_xyz_rpy({0.8, 0, top}, {0, 0, 0}), {1.0, 1.0, 0}), 0.05});
  w.add("box", make_clutter_box({0.1, 0.1, 0.1}), pose_from_xyz_rpy({0.8, 0.3, top}, {0, 0, 0}));
  const Eigen::Vector3d size(0.2, 0.2, 0.12);
  // Slightly high and tilted on free table: levelled onto the surface, same place.
  const Box found(pose_from_xyz_rpy({0.7, -0.2, top + 0.06}, {0.05, 0, 0.4}), size);
  const auto valid = w.free_patch_near("patch", found);
  ASSERT_TRUE(valid);
  EXPECT_NEAR(valid->translation().z(), top + 0.05, 1e-9);
  EXPECT_NEAR((valid->translation() - found.center()).head<2>().norm(), 0.0, 1e-9);
  EXPECT_GT(valid->linear().col(2).z(), 1.0 - 1e-9);
  // Overlapping the box by 2 cm: the nearest valid place is about 2 cm away.
  const Box overlapping(pose_from_xyz_rpy({0.8, 0.17, top + 0.05}, {0, 0, 0}), size);
  const auto shifted = w.free_patch_near("patch", overlapping);
  ASSERT_TRUE(shifted);
  EXPECT_NEAR((shifted->translation() - overlapping.center()).norm(), 0.0225, 0.0055);
  // Right over the box, or off the table: no valid patch near.
  EXPECT_FALSE(
      w.free_patch_near("patch", Box(pose_from_xyz_rpy({0.8, 0.3, top + 0.05}, {0, 0, 0}), size)));
  EXPECT_FALSE(
      w.free_patch_near("patch", Box(pose_from_xyz_rpy({1.35, 0, top + 0.05}, {0, 0, 0}), size)));
  EXPECT_FALSE(w.free_patch_near("other", found));
}

// The report's JSON without its wall-clock times, which differ from run to run.
std::string json_without_seconds(const std::string& json) {
  nlohmann::json j = nlohmann::json::parse(json);
  j.erase("seconds");
  for (auto& s : j["scenarios"]) s.erase("seconds");
  return j.dump();
}

// All six tasks once, shared by the tests below (about 15 s on two cores): run once per CTest run
// into a cache of the run (test::shared_run_data), which each test's process reads them from.
const DemoTasksReport& report() {
  static const DemoTasksReport r = [] {
    DemoTasksSettings settings;
    settings.cache_dir =
        test::shared_run_data("demo-tasks", [](const std::filesystem::path& cache) {
          DemoTasksSettings filling;
          filling.cache_dir = cache.string();
          run_demo_tasks(filling);
        }).string();
    return run_demo_tasks(settings);
  }();
  return r;
}

TEST(DemoTasks, RunTheSixTasksOfThePaperAndTheObstacles) {
  const DemoTasksReport& r = report();
  std::map<int, int> per_task;
  for (const DemoScenarioResult& s : r.scenarios) ++per_task[s.task];
  ASSERT_EQ(per_task.size(), 7u);  // the paper's six, and the obstacles (issue #60)
  for (const auto& [task, scenarios] : per_task) EXPECT_GE(scenarios, 5) << "task " << task;
  EXPECT_EQ(r.total(), r.scenarios.size());
  std::cout << demo_tasks_table(r);
}

// Safety, the paper's "should not act" cases: the robot refuses, names the missing landmark, and
// does not move.
TEST(DemoTasks, NeverActsWhenTheLandmarkIsMissing) {
  int cases = 0;
  for (const DemoScenarioResult& s : report().scenarios) {
    if (s.should_act || s.stopped) continue;  // stopped: carried off once planned (below)
    ++cases;
    EXPECT_TRUE(s.success) << "task " << s.task << ", " << s.name << ": " << s.reason;
    EXPECT_EQ(s.steps_executed, 0u) << s.name;
    EXPECT_EQ(s.reason.rfind("refused, no motion: landmark '", 0), 0u) << s.reason;
  }
  EXPECT_EQ(cases, 4);  // two in task 1, one each in tasks 3 and 4
}

// Issue #48: the trash bin pushed 11 cm, or carried off, as the arm arrives over it. Watching, the
// push is noticed and the rest re-planned to the bin's new place, and the carry stops the program
// with nothing sent after it; open loop (as before watching), the arm drops where the bin was.
TEST(DemoTasks, AMovedLandmarkIsNoticedWhenWatchedAndMissedOpenLoop) {
  const auto moved = [](const DemoTasksReport& r) {
    std::vector<DemoScenarioResult> out;
    for (const DemoScenarioResult& s : r.scenarios) {
      if (s.name.find("as the arm arrives") != std::string::npos) out.push_back(s);
    }
    return out;
  };
  const std::vector<DemoScenarioResult> watched = moved(report());
  ASSERT_EQ(watched.size(), 2u);
  EXPECT_TRUE(watched[0].success) << watched[0].reason;
  EXPECT_EQ(watched[0].replans, 1u);
  EXPECT_NE(watched[0].reason.find("'trash_opening' moved"), std::string::npos);
  EXPECT_TRUE(watched[1].success) << watched[1].reason;
  EXPECT_TRUE(watched[1].stopped);
  EXPECT_FALSE(watched[1].wrong_motion);
  EXPECT_NE(watched[1].reason.find("'trash_opening' is lost"), std::string::npos);

  DemoTasksSettings open_loop;
  open_loop.tasks = {4};
  open_loop.watch = false;
  const std::vector<DemoScenarioResult> unwatched = moved(run_demo_tasks(open_loop));
  ASSERT_EQ(unwatched.size(), 2u);
  for (const DemoScenarioResult& s : unwatched) {
    EXPECT_FALSE(s.success) << s.name;
    EXPECT_TRUE(s.wrong_motion) << s.name << ": " << s.reason;
  }
}

// A success is what the criterion says: targets within 2 cm and 10 degrees of the truth and the
// whole program executed; and every task succeeds in some scenario that acts, end to end.
TEST(DemoTasks, SuccessesMeetTheCriterionInEveryTask) {
  std::map<int, int> acted;
  for (const DemoScenarioResult& s : report().scenarios) {
    if (!s.should_act || !s.success) continue;
    ++acted[s.task];
    EXPECT_LE(s.max_position_error, 0.02) << s.name;
    EXPECT_LE(s.max_rotation_error, 10.0 * M_PI / 180.0) << s.name;
    EXPECT_GT(s.steps_executed, 0u) << s.name;
  }
  for (int task = 1; task <= 6; ++task) EXPECT_GE(acted[task], 1) << "task " << task;
}

// Issue #60: the bowls on the shelf with every motion checked. The shelf's roof and side panels
// rise above the head's first view; looking where the arm would go unseen before it goes, the arm
// touches the ground truth no more often than without looking, never moves wrongly, and succeeds
// as often.
TEST(DemoTasks, LookingWhereTheArmGoesUnseenTouchesNoMoreAndSucceedsAsOften) {
  DemoTasksSettings checked;
  checked.tasks = {3};
  checked.check_collisions = true;
  DemoTasksSettings blind = checked;
  blind.unseen_looks = 0;
  const DemoTasksReport looking = run_demo_tasks(checked), not_looking = run_demo_tasks(blind);
  std::size_t contacts[2] = {0, 0}, looks[2] = {0, 0};
  for (const auto& [k, r] : {std::pair{0, &looking}, std::pair{1, &not_looking}}) {
    for (const DemoScenarioResult& s : r->scenarios) {
      contacts[k] += s.contacts;
      looks[k] += s.looks;
      EXPECT_FALSE(s.wrong_motion) << s.name << ": " << s.reason;
    }
  }
  EXPECT_GT(looks[0], looks[1]);  // it did look where the arm goes
  EXPECT_LE(contacts[0], contacts[1]);
  EXPECT_EQ(looking.succeeded(), not_looking.succeeded());
}

// Issue #60: both hands on the chair's backrest with every motion checked. The second arm's target
// is chosen clear of the first arm at its own target: at 50 degrees the first IK solutions put the
// right upper arm into the left forearm, and the scenario was refused.
TEST(DemoTasks, BothHandsOnTheChairActWithEveryMotionChecked) {
  DemoTasksSettings checked;
  checked.tasks = {2};
  checked.check_collisions = true;
  const DemoTasksReport r = run_demo_tasks(checked);
  ASSERT_EQ(r.scenarios.size(), 5u);
  for (const DemoScenarioResult& s : r.scenarios) {
    EXPECT_TRUE(s.success) << s.name << ": " << s.reason;
    EXPECT_EQ(s.contacts, 0u) << s.name << ": " << s.first_contact;
  }
}

// Issue #60: task 7 stands something in the straight joint line's way in each of its scenarios.
// Unchecked, the arm touches it; checked, it goes around in at least 90% of them, touching
// nothing, never moving wrongly.
TEST(DemoTasks, TheObstaclesAreTouchedUncheckedAndGoneAroundChecked) {
  std::size_t unchecked_contacts = 0;
  for (const DemoScenarioResult& s : report().scenarios)
    if (s.task == 7) unchecked_contacts += s.contacts > 0;
  EXPECT_GE(unchecked_contacts, 8u);  // every one of them is in the way
  DemoTasksSettings checked;
  checked.tasks = {7};
  checked.check_collisions = true;
  // The planner's budget is its configurations checked, not the clock: the same paths on a loaded
  // machine.
  checked.motion_check.motion.planning_time = 1e6;
  const DemoTasksReport r = run_demo_tasks(checked);
  ASSERT_GE(r.scenarios.size(), 8u);
  std::size_t succeeded = 0;
  for (const DemoScenarioResult& s : r.scenarios) {
    succeeded += s.success;
    EXPECT_EQ(s.contacts, 0u) << s.name << ": " << s.first_contact;
    EXPECT_FALSE(s.wrong_motion) << s.name;
  }
  EXPECT_GE(10 * succeeded, 9 * r.scenarios.size());
}

TEST(DemoTasks, JsonHoldsEveryScenario) {
  const auto j = nlohmann::json::parse(demo_tasks_json(report()));
  ASSERT_EQ(j["scenarios"].size(), report().total());
  EXPECT_EQ(j["total"].get<std::size_t>(), report().total());
  EXPECT_EQ(j["succeeded"].get<std::size_t>(), report().succeeded());
  for (const auto& s : j["scenarios"]) {
    for (const char* key : {"task", "name", "should_act", "success", "reason"}) {
      EXPECT_TRUE(s.contains(key)) << key;
    }
  }
}

// Ctrl-C: the run stops after the scenario under way; finished tasks are cached, and the next
// run with the same cache takes them from there, with the same results.
TEST(DemoTasks, StopOnRequestAndResumeFromTheCache) {
  test::ScratchDir cache;
  DemoTasksSettings settings;
  settings.tasks = {3};
  settings.cache_dir = cache.path().string();
  settings.stop_requested = [] { return true; };
  try {
    run_demo_tasks(settings);
    ADD_FAILURE() << "the run did not stop";
  } catch (const Interrupted& e) {
    EXPECT_NE(std::string(e.what()).find("no task was finished"), std::string::npos) << e.what();
  }
  settings.stop_requested = nullptr;
  const DemoTasksReport first = run_demo_tasks(settings);
  ASSERT_FALSE(first.scenarios.empty());
  // Everything is cached now: a stop request has nothing left to interrupt.
  settings.stop_requested = [] { return true; };
  std::vector<std::string> lines;
  settings.progress = [&lines](const std::string& line) { lines.push_back(line); };
  const DemoTasksReport resumed = run_demo_tasks(settings);
  EXPECT_EQ(lines, std::vector<std::string>{"task 3: from the cache"});
  // The cache holds what the run computed.
  EXPECT_EQ(json_without_seconds(demo_tasks_json(resumed)),
            json_without_seconds(demo_tasks_json(first)));
}

TEST(DemoTasks, AnUnknownTaskIsAnError) {
  DemoTasksSettings settings;
  settings.tasks = {8};
  EXPECT_THROW(run_demo_tasks(settings), Error);
}

}  // namespace
}  // namespace lmk
