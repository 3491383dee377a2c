// SPDX-License-Identifier: BSD-3-Clause
// The robot's commands end to end: lmk robot (the PR2's FK and IK) and lmk pbd (show, plan, run and
// the demo tasks), with their refusals. Runs the real binary.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lmk/geometry/pose.h"
#include "tests/cli/cli_fixture.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using test::CommandResult;

TEST_F(Cli, RobotFkIkRoundTripAndRefusals) {
  const CommandResult fk =
      lmk("robot fk --group left_arm --torso 0.1 --joints 0.3 0.2 1.0 -1.0 0.5 -0.7 0.2 --json");
  ASSERT_EQ(fk.exit_code, 0) << fk.err;
  const auto pose = nlohmann::json::parse(fk.out);
  ASSERT_EQ(pose["position"].size(), 3u);
  ASSERT_EQ(pose["quaternion"].size(), 4u);
  // IK of that pose (given back as position and roll/pitch/yaw) lands within 1 mm of it.
  const Eigen::Quaterniond q(
      pose["quaternion"][0].get<double>(), pose["quaternion"][1].get<double>(),
      pose["quaternion"][2].get<double>(), pose["quaternion"][3].get<double>());
  const Eigen::Vector3d rpy = rpy_from_rotation(q.toRotationMatrix()) * 180.0 / M_PI;
  char args[256];
  std::snprintf(args, sizeof(args),
                "robot ik --group left_arm --torso 0.1 --position %.9f %.9f %.9f --rpy %.9f %.9f "
                "%.9f --json",
                pose["position"][0].get<double>(), pose["position"][1].get<double>(),
                pose["position"][2].get<double>(), rpy.x(), rpy.y(), rpy.z());
  const CommandResult ik = lmk(args);
  ASSERT_EQ(ik.exit_code, 0) << ik.err;
  const auto solution = nlohmann::json::parse(ik.out);
  EXPECT_EQ(solution["joints"].size(), 7u);
  EXPECT_LE(solution["position_error_m"].get<double>(), 0.001);
  EXPECT_LE(solution["rotation_error_rad"].get<double>(), 0.5 * M_PI / 180.0);

  const CommandResult far = lmk("robot ik --position 2.5 0 0.8 --rpy 0 0 0");
  EXPECT_EQ(far.exit_code, 1);
  EXPECT_EQ(far.err.rfind("lmk: unreachable: out of the workspace", 0), 0u) << far.err;
  expect_bad_input("robot fk --group tail --joints 0", "unknown group 'tail'");
  expect_bad_input("robot fk --joints 1 2", "has 7 joints, got 2");
  expect_bad_input("robot info --urdf " + path("missing.urdf"), "no such file");
  expect_bad_input("robot fk --torso 0.5 --joints 0 0 0 0 0 0 0", "torso height");
  EXPECT_NE(lmk("robot info").out.find("r_wrist_roll_joint"), std::string::npos);
}

// PbD from the command line, on task 4's recorded program and landmarks (trash vs recycling).
TEST_F(Cli, PbdShowPlanRunAndRefusals) {
  const CommandResult demo =
      lmk("pbd demo-tasks --task 4 --save " + path("demo") + " --json " + path("demo.json"));
  ASSERT_EQ(demo.exit_code, 0) << demo.err;
  EXPECT_NE(demo.out.find("succeeded"), std::string::npos) << demo.out;
  // The paper's five scenarios and issue #48's two where the trash bin moves as the arm arrives.
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_.file("demo.json")))["total"].get<int>(), 7);
  const std::string program = path("demo/task4/drop_in_trash.json");
  const std::string dir = dir_.file("demo/task4/");

  const CommandResult show = lmk("pbd show " + program);
  ASSERT_EQ(show.exit_code, 0) << show.err;
  EXPECT_NE(show.out.find("program 'drop in trash'"), std::string::npos) << show.out;
  EXPECT_NE(show.out.find("trash_opening"), std::string::npos) << show.out;

  // In the demonstration scene the landmark is where it was captured: the plan is valid.
  const CommandResult plan =
      lmk("pbd plan " + program + " --torso 0.05 --json --scene '" + dir + "demonstration.pcd'");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const auto j = nlohmann::json::parse(plan.out);
  EXPECT_TRUE(j["valid"].get<bool>());
  EXPECT_EQ(j["steps"].size(), 3u);
  EXPECT_EQ(j["landmarks"][0]["name"], "trash_opening");

  const CommandResult run =
      lmk("pbd run " + program + " --torso 0.05 --sim --scene '" + dir + "demonstration.pcd'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("executed step 0: right_arm to"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("done: 3 steps"), std::string::npos) << run.out;

  // Scenario 4 has only the recycling bin: a refusal, one line, exit 1.
  const CommandResult refused =
      lmk("pbd run " + program + " --torso 0.05 --sim --scene '" + dir + "scenario4.pcd'");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_EQ(refused.err.rfind("lmk: refused: landmark 'trash_opening' not found", 0), 0u)
      << refused.err;
  EXPECT_EQ(refused.out.find("executed"), std::string::npos) << refused.out;

  expect_bad_input("pbd run " + program + " --scene '" + dir + "demonstration.pcd'",
                   "give --sim --scene FILE for the simulated PR2, or --ros");
  expect_bad_input("pbd run " + program + " --ros --scene '" + dir + "demonstration.pcd'",
                   "pbd run --ros: --scene does not apply");
  expect_bad_input("pbd show " + path("missing.json"), "missing.json: no such file");
  expect_bad_input("pbd plan " + program + " --scene " + path("missing.pcd"), "missing.pcd");
  expect_bad_input(
      "pbd plan " + program + " --policy closest --scene '" + dir + "demonstration.pcd'",
      "unknown instance policy 'closest'");
  expect_bad_input("pbd demo-tasks --task 9", "no task 9");
}

}  // namespace
}  // namespace lmk
