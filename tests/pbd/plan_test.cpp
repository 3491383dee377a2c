// SPDX-License-Identifier: BSD-3-Clause
// Planning and executing on the simulated PR2: landmark-relative targets compose with where the
// landmark is found, and every refusal (a missing landmark, an unreachable step, a robot that
// moved) leaves the robot without a single motion.

#include "lmk/pbd/plan.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/pbd/execute.h"
#include "lmk/pr2/simulated_pr2.h"
#include "tests/pbd/robot_at_table.h"

namespace lmk {
namespace {

using test_scenes::box_at;
using test_scenes::kWorldBase;
using test_scenes::render_scene;
using test_scenes::scene_in_base;

// A gripper pointing down (its x axis along -z), `height` above the landmark box's centre.
Eigen::Isometry3d above(double height) {
  return pose_from_xyz_rpy({0, 0, height}, {0, 0.5 * M_PI, 0});
}

class PlanTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { landmark_ = new Landmark(test_scenes::demonstrated_l()); }
  static void TearDownTestSuite() { delete landmark_; }

  Program program() const {
    Program p;
    p.name = "touch l";
    p.landmarks = {{"l", "l.lmk"}};
    ProgramStep approach, touch, away;
    approach.right = ArmTarget{"l", above(0.2), GripperAction::kOpen};
    touch.right = ArmTarget{"l", above(0.12), GripperAction::kClose};
    away.right =
        ArmTarget{kBaseFrame, pose_from_xyz_rpy({0.5, -0.3, 1.0}, {0, 0, 0}), GripperAction::kOpen};
    p.steps = {approach, touch, away};
    return p;
  }

  // The torso raised 0.25 m, as a PR2 reaching down onto a table does.
  SimulatedPr2 robot() const { return test_scenes::robot_at_table(); }

  Plan plan_in(const PointCloud& scene, const Program& p, const SimulatedPr2& r,
               const PlanSettings& settings = {}) const {
    JointState state;
    EXPECT_TRUE(r.read_joint_state(state).ok());
    return plan(p, {{"l", *landmark_}}, scene, r.kinematics(), state, settings);
  }

  static Landmark* landmark_;
};

Landmark* PlanTest::landmark_ = nullptr;

TEST_F(PlanTest, TargetsComposeWithTheFoundLandmarkAndTheRobotGetsThere) {
  // The L moved 0.4 m to the robot's right (world +x) and 10 cm towards it.
  const Eigen::Vector2d moved(0.3, -0.25);
  SimulatedPr2 r = robot();
  const Plan p = plan_in(scene_in_base({moved}, true), program(), r);
  ASSERT_TRUE(p.valid()) << describe(*p.refusal);
  ASSERT_EQ(p.steps.size(), 3u);
  const LocatedLandmark* l = p.landmark("l");
  ASSERT_NE(l, nullptr);
  const Box truth = box_at(moved).transformed(kWorldBase.inverse());
  EXPECT_LT((l->T_base_landmark.translation() - truth.center()).norm(), 0.01);

  // Hand-computed: the box centre in the base frame is (0.65 + y_world_centre, -x_world_centre,
  // z); the first target is 0.2 m above it, pointing down.
  const Eigen::Vector3d centre = truth.center();
  EXPECT_NEAR(centre.x(), 0.65 + 0.5 * ((moved.y() - 0.04) + (moved.y() + 0.04)), 1e-9);
  const Eigen::Vector3d expected_first =
      l->T_base_landmark.translation() + Eigen::Vector3d(0, 0, 0.2);
  EXPECT_LT((p.steps[0].arms[0].T_base_ee.translation() - expected_first).norm(), 1e-3);
  EXPECT_LT(
      (p.steps[0].arms[0].T_base_ee.translation() - (centre + Eigen::Vector3d(0, 0, 0.2))).norm(),
      0.01);
  // The box's axes are the world's, so in the base frame it is turned by -90 degrees about z, and
  // the tool by that turn followed by the pitch that points it down.
  const Eigen::Matrix3d hand_computed =
      pose_from_xyz_rpy({0, 0, 0}, {0, 0, -0.5 * M_PI}).linear() * above(0).linear();
  EXPECT_LT(rotation_angle_between(p.steps[0].arms[0].T_base_ee.linear(), hand_computed),
            2.0 * M_PI / 180.0);
  // The base-frame step is taken as it is.
  EXPECT_TRUE(p.steps[2].arms[0].T_base_ee.isApprox(program().steps[2].right->T_frame_ee, 1e-12));

  const ExecutionReport report = execute(p, r);
  EXPECT_TRUE(report.completed) << report.error;
  EXPECT_EQ(report.steps_completed, 3u);
  EXPECT_EQ(r.history().size(), 3u);
  Eigen::Isometry3d tool;
  ASSERT_TRUE(r.kinematics().forward("right_arm", r.group_positions("right_arm"), tool).ok());
  EXPECT_LT((tool.translation() - p.steps[2].arms[0].T_base_ee.translation()).norm(), 1e-3);
  GripperState gripper;
  ASSERT_TRUE(r.gripper_state("right", gripper).ok());
  EXPECT_FALSE(gripper.closed);  // opened again by the last step
}

// Issue #60: a grasp demonstrated without its approach is reached from 10 cm back along the
// gripper's axis, fingers open, as a motion of its own; the robot passes through it.
TEST_F(PlanTest, AGraspWithoutItsApproachGainsOneAlongTheGrippersAxis) {
  Program p = program();
  p.steps.erase(p.steps.begin());  // from the robot's side straight onto the L
  p.steps.insert(p.steps.begin(), p.steps.back());
  p.steps.front().right->gripper = GripperAction::kOpen;
  SimulatedPr2 r = robot();
  const PointCloud scene = scene_in_base({{-0.1, -0.15}}, false);
  const Plan planned = plan_in(scene, p, r);
  ASSERT_TRUE(planned.valid()) << describe(*planned.refusal);
  ASSERT_GE(planned.steps.size(), 3u);
  const PlannedStep& approach = planned.steps[1];
  const PlannedStep& grasp = planned.steps[2];
  EXPECT_EQ(approach.index, 1u);
  EXPECT_EQ(approach.phase, Phase::kApproach);
  EXPECT_EQ(grasp.index, 1u);
  EXPECT_EQ(grasp.phase, Phase::kTarget);
  // 10 cm back along the grasp's x axis: pointing down, about 10 cm above it (the L's found
  // pose tilts by a fraction of a degree); the same way round, open.
  const Eigen::Isometry3d& T_pre = approach.arms.at(0).T_base_ee;
  const Eigen::Isometry3d& T_grasp = grasp.arms.at(0).T_base_ee;
  EXPECT_LT((T_pre.translation() - T_grasp * Eigen::Vector3d(-0.1, 0, 0)).norm(), 1e-9);
  EXPECT_LT((T_pre.translation() - T_grasp.translation() - Eigen::Vector3d(0, 0, 0.1)).norm(),
            1e-3);
  EXPECT_LT(rotation_angle_between(T_pre.linear(), T_grasp.linear()), 1e-9);
  EXPECT_EQ(approach.arms.at(0).gripper, GripperAction::kOpen);

  const ExecutionReport report = execute(planned, r);
  EXPECT_TRUE(report.completed) << report.error;
  EXPECT_EQ(r.history().size(), planned.steps.size());

  PlanSettings none;
  none.approach = 0.0;
  const Plan straight = plan_in(scene, p, r, none);
  ASSERT_TRUE(straight.valid()) << describe(*straight.refusal);
  EXPECT_EQ(straight.steps.size(), p.steps.size());
  none.approach = -0.1;
  EXPECT_THROW(plan_in(scene, p, r, none), Error);
}

TEST_F(PlanTest, AMissingLandmarkIsRefusedByNameAndNothingMoves) {
  SimulatedPr2 r = robot();
  const Plan p = plan_in(scene_in_base({}, true), program(), r);
  ASSERT_FALSE(p.valid());
  const auto* missing = std::get_if<LandmarkNotFound>(&*p.refusal);
  ASSERT_NE(missing, nullptr) << describe(*p.refusal);
  EXPECT_EQ(missing->landmark, "l");
  EXPECT_TRUE(p.steps.empty());
  const ExecutionReport report = execute(p, r);
  EXPECT_FALSE(report.started);
  EXPECT_NE(report.error.find("landmark 'l' not found"), std::string::npos) << report.error;
  EXPECT_TRUE(r.history().empty());
  EXPECT_EQ(r.time(), 0.0);  // not even a gripper moved
}

TEST_F(PlanTest, ADoubtfulLandmarkIsRefusedWithItsConfidenceAndNothingMoves) {
  // Two copies of the L: each is the other's look-alike. Found, but no surer than the cut asks.
  const PointCloud scene = scene_in_base({{0.3, -0.25}, {-0.1, -0.15}}, false);
  SimulatedPr2 r = robot();
  PlanSettings settings;
  const Plan acting = plan_in(scene, program(), r, settings);
  ASSERT_NE(acting.landmark("l"), nullptr) << describe(*acting.refusal);
  const double confidence = acting.landmark("l")->match.confidence.probability;
  ASSERT_GT(confidence, 0.0);
  ASSERT_LT(confidence, 1.0);
  settings.min_confidence = 0.5 * (confidence + 1.0);  // above every instance's confidence
  const Plan p = plan_in(scene, program(), r, settings);
  ASSERT_FALSE(p.valid());
  const auto* doubtful = std::get_if<LandmarkDoubtful>(&*p.refusal);
  ASSERT_NE(doubtful, nullptr) << describe(*p.refusal);
  EXPECT_EQ(doubtful->landmark, "l");
  EXPECT_LT(doubtful->confidence, settings.min_confidence);
  EXPECT_EQ(doubtful->min_confidence, settings.min_confidence);
  EXPECT_EQ(doubtful->competitor.kind, Competitor::Kind::look_alike);
  EXPECT_EQ(std::string(refusal_kind(*p.refusal)), "landmark-doubtful");
  EXPECT_NE(describe(*p.refusal).find("'l'"), std::string::npos) << describe(*p.refusal);
  EXPECT_TRUE(p.steps.empty());
  const ExecutionReport report = execute(p, r);
  EXPECT_FALSE(report.started);
  EXPECT_TRUE(r.history().empty());
  EXPECT_EQ(r.time(), 0.0);
}

TEST_F(PlanTest, AnUnreachableStepIsRefusedBeforeTheReachableOnesRun) {
  Program far = program();
  ProgramStep out_of_reach;
  out_of_reach.left =
      ArmTarget{kBaseFrame, pose_from_xyz_rpy({2.5, 0.5, 0.8}, {0, 0, 0}), GripperAction::kOpen};
  far.steps.push_back(out_of_reach);
  SimulatedPr2 r = robot();
  const Plan p = plan_in(scene_in_base({{-0.1, -0.15}}, false), far, r);
  ASSERT_FALSE(p.valid());
  const auto* unreachable = std::get_if<Unreachable>(&*p.refusal);
  ASSERT_NE(unreachable, nullptr) << describe(*p.refusal);
  EXPECT_EQ(unreachable->step, 3u);
  EXPECT_EQ(unreachable->arm, Arm::kLeft);
  EXPECT_FALSE(unreachable->reason.empty());
  EXPECT_FALSE(execute(p, r).started);
  EXPECT_TRUE(r.history().empty());
  EXPECT_EQ(r.time(), 0.0);
}

// Three L-shapes, the one the policy prefers out of reach: the planner takes the next one the arm
// can reach, unless told not to.
TEST_F(PlanTest, AnOutOfReachInstanceGivesWayToTheNextOne) {
  // The robot stands at the table's left end, facing along it: the copies' boxes are about 0.55,
  // 0.9 and 1.3 m in front of it, and the policy prefers the far end.
  const Eigen::Isometry3d world_base = pose_from_xyz_rpy({-0.95, -0.1, 0}, {0, 0, 0});
  const PointCloud scene =
      render_scene(test_scenes::kCopies, true).transformed(world_base.inverse());
  Program p = program();
  p.landmarks[0].select = InstancePolicy::kNearestToDemonstration;
  p.landmarks[0].demonstration =
      box_at(test_scenes::kCopies[2]).transformed(world_base.inverse()).pose;
  SimulatedPr2 r = robot();
  JointState state;
  ASSERT_TRUE(r.read_joint_state(state).ok());
  const Plan fallback = plan(p, {{"l", *landmark_}}, scene, r.kinematics(), state);
  ASSERT_TRUE(fallback.valid()) << describe(*fallback.refusal);
  const double chosen = fallback.landmark("l")->T_base_landmark.translation().x();
  EXPECT_LT(chosen, 1.0);  // not the far copy
  EXPECT_GE(fallback.landmark("l")->eligible, 2u);

  PlanSettings strict;
  strict.try_other_instances = false;
  const Plan refused = plan(p, {{"l", *landmark_}}, scene, r.kinematics(), state, strict);
  ASSERT_FALSE(refused.valid());
  const auto* unreachable = std::get_if<Unreachable>(&*refused.refusal);
  ASSERT_NE(unreachable, nullptr) << describe(*refused.refusal);
  EXPECT_EQ(unreachable->step, 0u);
  // Refused with the preferred instance (the farthest found), which the fallback passed over.
  EXPECT_GT(refused.landmark("l")->T_base_landmark.translation().x(), chosen + 0.2);
}

TEST_F(PlanTest, ARobotThatMovedSincePlanningIsNotDriven) {
  SimulatedPr2 r = robot();
  const Plan p = plan_in(scene_in_base({{-0.1, -0.15}}, false), program(), r);
  ASSERT_TRUE(p.valid());
  // Someone moves the right arm's first joint after planning.
  const GroupInfo arm = *r.kinematics().group("right_arm");
  JointTrajectory nudge;
  for (const JointInfo& j : arm.joints) nudge.joint_names.push_back(j.name);
  std::vector<double> q = r.group_positions("right_arm");
  q[0] += 0.2;
  nudge.points.push_back({q, 2.0});
  ASSERT_TRUE(r.send_trajectory("right_arm", nudge).ok());
  const ExecutionReport report = execute(p, r);
  EXPECT_FALSE(report.started);
  EXPECT_NE(report.error.find("moved since planning"), std::string::npos) << report.error;
  EXPECT_EQ(r.history().size(), 1u);  // only the nudge
}

TEST_F(PlanTest, AnInactiveRobotStopsTheRunAtTheFirstCommandAndSaysWhere) {
  SimulatedPr2 r = robot();
  const Plan p = plan_in(scene_in_base({{-0.1, -0.15}}, false), program(), r);
  ASSERT_TRUE(p.valid());
  ASSERT_TRUE(r.deactivate().ok());
  const ExecutionReport report = execute(p, r);
  EXPECT_TRUE(report.started);
  EXPECT_FALSE(report.completed);
  EXPECT_EQ(report.steps_completed, 0u);
  EXPECT_NE(report.error.find("step 0"), std::string::npos) << report.error;
  EXPECT_TRUE(r.history().empty());
}

}  // namespace
}  // namespace lmk
