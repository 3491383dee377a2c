// SPDX-License-Identifier: BSD-3-Clause
// lmk on ROS 1, end to end against a real rosmaster of the test's own (tests/ros/support):
// `lmk pbd run --ros` driving the fake PR2's controllers, and RosRobot's lifecycle. The scenes,
// landmark and program are the paper's task 3 ("bowls on a shelf") from lmk's demo tasks
// (node_fixture.h): its demonstration frame, a frame where the bowl can be picked, and one with
// only cups, where the robot must not act.

#include <actionlib/server/action_server.h>
#include <geometry_msgs/PointStamped.h>
#include <gtest/gtest.h>
#include <lmk_msgs/AddView.h>
#include <lmk_msgs/CaptureLandmark.h>
#include <lmk_msgs/FindLandmark.h>
#include <lmk_msgs/ListLandmarks.h>
#include <lmk_msgs/Track.h>
#include <lmk_msgs/TrackedLandmarks.h>
#include <pr2_controllers_msgs/JointTrajectoryAction.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>
#include <utility>

#include "lmk/demos/demo_tasks.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/range_image.h"
#include "lmk/landmark/box_guess.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/ros/cloud_conversion.h"
#include "lmk/ros/geometry_conversion.h"
#include "lmk/ros/latest_frame.h"
#include "lmk/ros/ros_robot.h"
#include "tests/ros/node_fixture.h"
#include "tests/ros/support/fake_pr2.h"
#include "tests/ros/support/ros_harness.h"
#include "tests/support/lifecycle_conformance.h"
#include "tests/support/test_support.h"

namespace lmk::test {
namespace {

namespace fs = std::filesystem;

/// The plan `lmk pbd run --ros` makes: the same frame, joint state, torso and settings.
Plan expected_plan(const FakePr2& robot) {
  const Program program = load_program(demo_data().program().string());
  const auto landmarks = load_program_landmarks(program, demo_data().task.string());
  JointState state;
  for (const auto& [name, q] : robot.joints()) {
    state.names.push_back(name);
    state.positions.push_back(q);
    state.velocities.push_back(0.0);
  }
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  return plan(program, landmarks, frame_as_the_node_sees_it().scene, kinematics, state);
}

const char* arm_action(Arm arm) {
  return arm == Arm::kLeft ? "l_arm_controller/joint_trajectory_action"
                           : "r_arm_controller/joint_trajectory_action";
}

TEST(PbdRunOnRos, DrivesThePr2WithExactlyThePlannedTrajectories) {
  FakePr2 robot(fake_settings("scenario3.pcd"));
  const Plan plan = expected_plan(robot);
  ASSERT_TRUE(plan.valid()) << describe(*plan.refusal);
  ASSERT_FALSE(plan.steps.empty());
  const ScratchDir dir;
  // Unchecked, as the plan above: the checked run's goals are another test's.
  const auto [code, out] = run_lmk(
      dir, {"pbd", "run", demo_data().program().string(), "--ros", "--no-check-collisions"});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("done"), std::string::npos) << out;

  std::map<std::string, std::size_t> next;
  for (const PlannedStep& step : plan.steps) {
    for (const PlannedArm& a : step.arms) {
      const auto sent = robot.trajectories(arm_action(a.arm));
      const std::size_t k = next[arm_action(a.arm)]++;
      ASSERT_LT(k, sent.size()) << "step " << step.index << ": no goal for " << arm_name(a.arm);
      const trajectory_msgs::JointTrajectory& got = sent[k];
      EXPECT_EQ(got.joint_names, a.trajectory.joint_names);
      ASSERT_EQ(got.points.size(), a.trajectory.points.size());
      for (std::size_t p = 0; p < got.points.size(); ++p) {
        EXPECT_EQ(got.points[p].positions, a.trajectory.points[p].positions);
        EXPECT_NEAR(got.points[p].time_from_start.toSec(), a.trajectory.points[p].time_from_start,
                    1e-9);
      }
    }
  }
  ASSERT_FALSE(next.empty());
  for (const auto& [action, used] : next) EXPECT_EQ(robot.goals(action), static_cast<int>(used));
  // Each step's gripper too, on the arm that moved.
  EXPECT_EQ(robot.goals("r_gripper_controller/gripper_action"),
            static_cast<int>(next["r_arm_controller/joint_trajectory_action"]));
}

int arm_and_gripper_goals(const FakePr2& robot) {
  return robot.total_goals() - robot.goals("head_traj_controller/point_head_action");
}

TEST(PbdRunOnRos, AMissingLandmarkSendsNoArmGoalAfterLookingAgain) {
  FakePr2 robot(fake_settings("scenario5.pcd"));  // only cups
  const ScratchDir dir;
  // The head looks twice (--look-again's default), sees no bowl either time, and the run refuses
  // naming both looks.
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("refused: landmark 'bowl_rim' not found"), std::string::npos) << out;
  EXPECT_NE(out.find("after 2 more looks (at ("), std::string::npos) << out;
  EXPECT_EQ(robot.goals("head_traj_controller/point_head_action"), 2);
  EXPECT_EQ(arm_and_gripper_goals(robot), 0);
  // --look-again 0 refuses at once: not even the head moves.
  const auto [code2, out2] =
      run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--look-again", "0"});
  EXPECT_EQ(code2, 1) << out2;
  EXPECT_EQ(out2.find("more look"), std::string::npos) << out2;
  EXPECT_EQ(robot.goals("head_traj_controller/point_head_action"), 2);
  EXPECT_EQ(arm_and_gripper_goals(robot), 0);
}

TEST(PbdRunOnRos, AMotionThatWouldTouchAndCannotGoAroundSendsNoArmGoal) {
  FakePr2 robot(fake_settings("scenario3.pcd"));  // the bowl is there: only the motion refuses
  const ScratchDir dir;
  // 20 cm of padding from the shelf and a planner allowed one configuration: the first motion
  // would come too near, and no way around it is found. Nothing moves, not even the head.
  const auto [code, out] =
      run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--check-collisions",
                    "--padding", "0.2", "--planning-checks", "1", "--look-again", "0",
                    "--unseen-looks", "0"});
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("refused: step 0, right arm: link "), std::string::npos) << out;
  EXPECT_NE(out.find(" m in base_link"), std::string::npos) << out;
  EXPECT_EQ(robot.total_goals(), 0);
}

TEST(PbdRunOnRos, TheCollisionModelIsReadFromRobotDescription) {
  FakePr2 robot(fake_settings("scenario3.pcd"));
  struct Param {  // a parameter for this test only, whatever fails
    Param(std::string name, const std::string& value) : name_(std::move(name)) {
      ::ros::param::set(name_, value);
    }
    ~Param() { ::ros::param::del(name_); }
    std::string name_;
  };
  const ScratchDir dir;
  const std::vector<std::string> run = {"pbd", "run", demo_data().program().string(), "--ros",
                                        "--check-collisions"};
  std::ifstream in(std::string(LMK_SOURCE_DIR) + "/pr2/data/pr2.urdf");
  const std::string urdf(std::istreambuf_iterator<char>(in), {});
  {
    // With MoveIt's SRDF beside it: its pairs of links that may touch are taken.
    const Param pr2("/robot_description", urdf);
    const Param semantic("/robot_description_semantic", R"(<robot name="pr2">
      <disable_collisions link1="r_gripper_palm_link" link2="l_gripper_palm_link"/>
      <disable_collisions link1="r_forearm_link" link2="l_forearm_link"/></robot>)");
    const auto [code, out] = run_lmk(dir, run);
    EXPECT_EQ(code, 0) << out;
    EXPECT_NE(out.find("collision model: robot_description's pr2, "), std::string::npos) << out;
    EXPECT_NE(out.find("2 pairs of links that may touch from robot_description_semantic"),
              std::string::npos)
        << out;
  }
  const int goals = robot.total_goals();
  for (const auto& [name, value, said] :
       {std::tuple<std::string, std::string, std::string>{
            "/robot_description", "<robot name=\"broken\"></robot>", "robot_description"},
        {"/robot_description_semantic", "<robot><disable_collisions link1=\"a\"/></robot>",
         "robot_description_semantic: a <disable_collisions> element"}}) {
    // A description that is no robot, an SRDF that is broken: one clear line, nothing moves.
    const Param description("/robot_description", urdf);
    const Param broken(name, value);
    const auto [code, out] = run_lmk(dir, run);
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("pbd run --ros: "), std::string::npos) << out;
    EXPECT_NE(out.find(said), std::string::npos) << out;
    EXPECT_EQ(robot.total_goals(), goals);
  }
}

/// The PR2's arms as the fake PR2 starts them: every joint at zero, or at its nearest limit.
JointState arms_at_rest(const Pr2Kinematics& kinematics) {
  JointState state;
  for (const char* group : {"left_arm", "right_arm"}) {
    const GroupInfo info = *kinematics.group(group);  // alive while its joints are read
    for (const JointInfo& j : info.joints) {
      state.names.push_back(j.name);
      state.positions.push_back(j.continuous() ? 0.0 : std::clamp(0.0, j.lower, j.upper));
      state.velocities.push_back(0.0);
    }
  }
  return state;
}

/// `scene` as a camera whose image ends before `box`: every pixel on the box's side of the image,
/// from the box's nearest corner on, returns nothing.
PointCloud cut_by_the_image_edge(const PointCloud& scene, const Box& box) {
  const Eigen::Isometry3d T_sensor_cloud = scene.T_cloud_sensor.inverse();
  const double side = (T_sensor_cloud * box.pose.translation()).x() > 0.0 ? 1.0 : -1.0;
  double edge = std::numeric_limits<double>::infinity();  // in x/z, the image's column
  for (const Eigen::Vector3d& corner : box.corners()) {
    const Eigen::Vector3d c = T_sensor_cloud * corner;
    edge = std::min(edge, side * c.x() / c.z());
  }
  PointCloud cut = scene;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < cut.size(); ++i) {
    const Eigen::Vector3d p = T_sensor_cloud * cut.points[i].cast<double>();
    if (std::isfinite(p.z()) && side * p.x() / p.z() >= edge - 0.02) {
      cut.points[i].setConstant(nan);
      if (cut.has_normals()) cut.normals[i].setConstant(nan);
    }
  }
  return cut;
}

// Looking again (issue #46): the first view's image ends before the bowl; the head turns, the
// camera then sees it whole, the new frame is fused with the first and the program runs.
TEST(PbdRunOnRos, ALandmarkTheFirstViewCutIsFoundByLookingAgain) {
  const PointCloud whole = demo_data().scene("scenario3.pcd");
  const Program program = load_program(demo_data().program().string());
  const auto landmarks = load_program_landmarks(program, demo_data().task.string());
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  const JointState rest = arms_at_rest(kinematics);
  const Plan in_whole = plan(program, landmarks, whole, kinematics, rest);
  ASSERT_TRUE(in_whole.valid()) << describe(*in_whole.refusal);
  const LocatedLandmark* bowl = in_whole.landmark("bowl_rim");
  ASSERT_NE(bowl, nullptr);
  const PointCloud cut = cut_by_the_image_edge(whole, bowl->match.box);
  // The cut frame alone does not show the bowl: without looking again the robot would refuse.
  const Plan in_cut = plan(program, landmarks, cut, kinematics, rest);
  ASSERT_FALSE(in_cut.valid());
  ASSERT_TRUE(std::holds_alternative<LandmarkNotFound>(*in_cut.refusal))
      << describe(*in_cut.refusal);

  FakePr2Settings settings = fake_settings("scenario3.pcd");
  settings.scene = cut;
  settings.scenes_after_head_goals = {whole};
  FakePr2 robot(settings);
  const ScratchDir dir;
  // Unchecked: the head's one look is the landmark's, none where the arm would go.
  const auto [code, out] = run_lmk(
      dir, {"pbd", "run", demo_data().program().string(), "--ros", "--no-check-collisions"});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("looked again at ("), std::string::npos) << out;
  EXPECT_NE(out.find("for the missing 'bowl_rim'"), std::string::npos) << out;
  EXPECT_NE(out.find("done"), std::string::npos) << out;
  EXPECT_EQ(robot.goals("head_traj_controller/point_head_action"), 1);
  EXPECT_GT(robot.goals("r_arm_controller/joint_trajectory_action") +
                robot.goals("l_arm_controller/joint_trajectory_action"),
            0);
}

TEST(PbdRunOnRos, AnAbortedArmGoalStopsTheRunAndNamesTheStep) {
  FakePr2 robot(fake_settings("scenario3.pcd"));
  robot.abort_arm_goal(2);
  const ScratchDir dir;
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("stopped after 1 of"), std::string::npos) << out;
  EXPECT_NE(out.find("step 1: right_arm: r_arm_controller/joint_trajectory_action: the "
                     "controller aborted the goal (fake PR2: the test asked for an abort)"),
            std::string::npos)
      << out;
  int arm_goals = 0;
  for (Arm arm : {Arm::kLeft, Arm::kRight}) arm_goals += robot.goals(arm_action(arm));
  EXPECT_EQ(arm_goals, 2);  // nothing after the abort
}

// The boxes of the bowls lmk finds in `scene` (base_link), each grown by 4 cm on every side: what
// a person who takes or moves a bowl takes along (the table under it too).
std::vector<Box> around_the_bowls(const PointCloud& scene) {
  FindSettings find;
  find.scene.base_frame = true;
  const FindResult bowls =
      find_landmark(scene, load_landmark(demo_data().landmark().string()), find);
  std::vector<Box> around;
  for (const Match& bowl : bowls.matches)
    around.emplace_back(bowl.box.pose, bowl.box.size + Eigen::Vector3d::Constant(0.08));
  return around;
}

bool in_any(const std::vector<Box>& boxes, const Eigen::Vector3f& p) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const Box& b) { return b.contains(p); });
}

// `scene` (organised) with the points in `moved` shifted by `shift`, as its camera would see it
// then: every point projected onto its pixel again, the nearest kept.
PointCloud seen_after_moving(const PointCloud& scene, const std::vector<Box>& moved,
                             const Eigen::Vector3f& shift) {
  const std::optional<RangeImage> image = RangeImage::from_cloud(scene);
  EXPECT_TRUE(image && image->organised());
  PointCloud out = scene;
  std::fill(out.points.begin(), out.points.end(),
            Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  std::vector<float> nearest(scene.size(), std::numeric_limits<float>::infinity());
  const Eigen::Vector3f sensor = scene.sensor_origin().cast<float>();
  for (std::size_t i = 0; i < scene.size(); ++i) {
    Eigen::Vector3f p = scene.points[i];
    if (!p.allFinite()) continue;
    if (in_any(moved, p)) p += shift;
    const std::optional<Eigen::Vector2d> pixel = image->project(p);
    if (!pixel) continue;
    const long u = std::lround(pixel->x()), v = std::lround(pixel->y());
    if (u < 0 || v < 0 || u >= static_cast<long>(scene.width) ||
        v >= static_cast<long>(scene.height))
      continue;
    const std::size_t k = static_cast<std::size_t>(v) * scene.width + static_cast<std::size_t>(u);
    const float range = (p - sensor).norm();
    if (range >= nearest[k]) continue;
    nearest[k] = range;
    out.points[k] = p;
    if (!scene.colors.empty()) out.colors[k] = scene.colors[i];
  }
  return out;
}

// Where the right gripper ends the `n`-th (0-based) trajectory the fake PR2 received.
Eigen::Vector3d right_gripper_after(const FakePr2& robot, std::size_t n) {
  const auto sent = robot.trajectories(arm_action(Arm::kRight));
  EXPECT_LT(n, sent.size());
  if (n >= sent.size()) return Eigen::Vector3d::Constant(std::nan(""));
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  const GroupInfo arm = *kinematics.group("right_arm");
  std::vector<double> joints;
  for (const JointInfo& j : arm.joints) {
    const auto& names = sent[n].joint_names;
    const auto at = std::find(names.begin(), names.end(), j.name);
    EXPECT_NE(at, names.end()) << j.name;
    if (at == names.end()) return Eigen::Vector3d::Constant(std::nan(""));
    joints.push_back(sent[n].points.back().positions[at - names.begin()]);
  }
  Eigen::Isometry3d T_base_tool;
  EXPECT_TRUE(kinematics.forward("right_arm", joints, T_base_tool).ok());
  return T_base_tool.translation();
}

TEST(PbdRunOnRos, WatchingReplansWhenTheLandmarkIsMovedWhileTheArmMoves) {
  // pick_bowl: approach, grasp and lift relative to the bowl, then a place in the base frame. The
  // bowls are pushed 5 cm to the robot's left once the approach is under way.
  FakePr2Settings settings = fake_settings("scenario1.pcd");
  const std::vector<Box> bowls = around_the_bowls(settings.scene);
  ASSERT_FALSE(bowls.empty());
  const Eigen::Vector3f push(0.0f, 0.05f, 0.0f);
  settings.scenes_after_arm_goals = {seen_after_moving(settings.scene, bowls, push)};

  const ScratchDir dir;
  Eigen::Vector3d grasp_watched;
  {
    FakePr2 robot(settings);
    const auto [code, out] =
        run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--watch"});
    ASSERT_EQ(code, 0) << out;
    EXPECT_NE(out.find("re-planned the remaining"), std::string::npos) << out;
    // Noticed before the approach's gripper command: the approach again towards the bowl where it
    // is now, then grasp, lift and place.
    const auto sent = robot.trajectories(arm_action(Arm::kRight));
    ASSERT_EQ(sent.size(), 5u) << out;
    grasp_watched = right_gripper_after(robot, 2);
  }
  FakePr2 robot(settings);
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  ASSERT_EQ(code, 0) << out;  // open loop: it grasps where the bowl was
  ASSERT_EQ(robot.trajectories(arm_action(Arm::kRight)).size(), 4u) << out;
  const Eigen::Vector3d grasp_open_loop = right_gripper_after(robot, 1);
  // The watched grasp followed the bowl; the open-loop one did not.
  const Eigen::Vector3d followed = grasp_watched - grasp_open_loop;
  EXPECT_NEAR(followed.y(), push.y(), 0.01) << followed.transpose();
  EXPECT_LT(std::hypot(followed.x(), followed.z()), 0.01) << followed.transpose();
}

// Issue #48, --watch: the bowl is taken away once the arm has its first goal. Watching, the run
// notices before the gripper moves and stops, sending nothing more; unwatched, it goes on.
TEST(PbdRunOnRos, WatchingStopsWhenTheLandmarkIsTakenWhileTheArmMoves) {
  FakePr2Settings settings = fake_settings("scenario1.pcd");
  // The scene without its bowls: every instance's box emptied (with one left, the watch would
  // rightly follow the program to it).
  const std::vector<Box> bowls = around_the_bowls(settings.scene);
  ASSERT_FALSE(bowls.empty());
  PointCloud taken = settings.scene;
  for (Eigen::Vector3f& p : taken.points) {
    if (p.allFinite() && in_any(bowls, p)) p.setConstant(std::numeric_limits<float>::quiet_NaN());
  }
  settings.scenes_after_arm_goals = {taken};

  const ScratchDir dir;
  {
    FakePr2 robot(settings);
    const auto [code, out] =
        run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--watch"});
    EXPECT_EQ(code, 1) << out;
    EXPECT_NE(out.find("landmark 'bowl_rim' is lost: stopped rather than move towards where it "
                       "was"),
              std::string::npos)
        << out;
    int arm_goals = 0;
    for (Arm arm : {Arm::kLeft, Arm::kRight}) arm_goals += robot.goals(arm_action(arm));
    EXPECT_EQ(arm_goals, 1);  // the first only: no arm goal after the bowls went
  }
  FakePr2 robot(settings);
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code, 0) << out;  // open loop: it never looked again, and went on
  int arm_goals = 0;
  for (Arm arm : {Arm::kLeft, Arm::kRight}) arm_goals += robot.goals(arm_action(arm));
  EXPECT_GT(arm_goals, 1);
}

TEST(PbdRunOnRos, NoMasterOrNoRobotIsOneClearLine) {
  const ScratchDir dir;
  const auto [code, out] = run_to_end({"env", "ROS_MASTER_URI=http://127.0.0.1:1/", LMK_BINARY,
                                       "pbd", "run", demo_data().program().string(), "--ros"},
                                      dir.file("no_master.log"));
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("lmk: error: pbd run --ros: no ROS master at http://127.0.0.1:1/"),
            std::string::npos)
      << out;
  // A master, but no robot: configure names every controller and topic that did not answer.
  const auto [code2, out2] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code2, 2) << out2;
  EXPECT_NE(out2.find("lmk: error: pbd run --ros: configure: no answer within 5.0 s from "
                      "l_arm_controller/joint_trajectory_action"),
            std::string::npos)
      << out2;
}

TEST(RosRobot, AnswersEveryMethodInEveryStateAsTheInterfaceDocuments) {
  FakePr2 fake(fake_settings("demonstration.pcd"));
  ros1::RosRobot robot{::ros::NodeHandle()};
  expect_lifecycle_table(robot, *Pr2Kinematics().group("left_arm"), "left");
  EXPECT_GE(fake.goals("l_arm_controller/joint_trajectory_action"), 1);
}

TEST(RosRobot, AGoalWithoutResultInTimeIsCancelledAndReturnedAsAnError) {
  FakePr2 fake(fake_settings("demonstration.pcd"));
  fake.hang_arm_goal(1);
  ros1::RosRobotSettings settings;
  settings.result_margin = 1.0;
  ros1::RosRobot robot(::ros::NodeHandle(), settings);
  ASSERT_TRUE(robot.configure().ok());
  ASSERT_TRUE(robot.activate().ok());
  JointTrajectory hold;
  JointTrajectory::Point point;
  const std::map<std::string, double> joints = fake.joints();
  const GroupInfo arm = *Pr2Kinematics().group("right_arm");  // alive while its joints are read
  for (const JointInfo& j : arm.joints) {
    hold.joint_names.push_back(j.name);
    point.positions.push_back(joints.at(j.name));
  }
  point.time_from_start = 0.5;
  hold.points.push_back(point);
  const CallResult r = robot.send_trajectory("right_arm", hold);  // 0.5 s + 1 s margin
  EXPECT_EQ(r.status, Status::kError);
  EXPECT_NE(r.message.find("r_arm_controller/joint_trajectory_action: no result within 1.5 s; "
                           "the goal was cancelled"),
            std::string::npos)
      << r.message;
  for (int i = 0; i < 200 && fake.cancelled_goals() == 0; ++i) ::ros::WallDuration(0.01).sleep();
  EXPECT_EQ(fake.cancelled_goals(), 1);
  EXPECT_EQ(robot.state(), LifecycleState::kActive);
  EXPECT_TRUE(robot.send_trajectory("right_arm", hold).ok());  // the next goal runs
}

TEST(RosRobot, ARejectedGoalIsReturnedAsAnError) {
  FakePr2 fake(fake_settings("demonstration.pcd"));
  // A controller that rejects every goal, standing in for the right arm's.
  using Server = actionlib::ActionServer<pr2_controllers_msgs::JointTrajectoryAction>;
  ::ros::NodeHandle nh;
  // The server's callbacks run on a queue of its own, whose spinner is destroyed before the server
  // (declared after it): ~RosRobot cancels its goals, and on the global queue that cancel could
  // reach the server while it is destroyed, which aborted roscpp ('null Publication').
  ::ros::CallbackQueue strict_queue;
  ::ros::NodeHandle strict_nh;
  strict_nh.setCallbackQueue(&strict_queue);
  Server strict(
      strict_nh, "strict_arm/joint_trajectory_action",
      [](Server::GoalHandle goal) {
        goal.setRejected(pr2_controllers_msgs::JointTrajectoryResult(), "joints out of range");
      },
      false);
  strict.start();
  ::ros::AsyncSpinner strict_spinner(1, &strict_queue);
  strict_spinner.start();
  ros1::RosRobotSettings settings;
  settings.arm_actions = {{"left_arm", "l_arm_controller/joint_trajectory_action"},
                          {"right_arm", "strict_arm/joint_trajectory_action"}};
  ros1::RosRobot robot(nh, settings);
  ASSERT_TRUE(robot.configure().ok());
  ASSERT_TRUE(robot.activate().ok());
  JointTrajectory t;
  t.joint_names = {"r_shoulder_pan_joint"};
  t.points.push_back({{0.0}, 1.0});
  const CallResult r = robot.send_trajectory("right_arm", t);
  EXPECT_EQ(r.status, Status::kError);
  EXPECT_EQ(r.message,
            "strict_arm/joint_trajectory_action: the controller rejected the goal (joints out of "
            "range)");
}

TEST(RosRobot, ConfigureNamesWhatDoesNotAnswer) {
  ros1::RosRobotSettings settings;
  settings.connect_timeout = 1.0;
  ros1::RosRobot robot(::ros::NodeHandle(), settings);
  const CallResult r = robot.configure();
  EXPECT_EQ(r.status, Status::kError);
  EXPECT_NE(r.message.find("l_arm_controller/joint_trajectory_action"), std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("joint_states"), std::string::npos) << r.message;
  EXPECT_EQ(robot.state(), LifecycleState::kUnconfigured);
}

}  // namespace
}  // namespace lmk::test
