// SPDX-License-Identifier: BSD-3-Clause
// Checked arm motions (issue #60) on scenes built here: a straight joint line through a box is
// refused and planned around; space hidden behind a plate blocks a motion when unknown counts as
// occupied and not when it counts as free; an object the gripper means to touch does not block it.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "lmk/geometry/solid.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/robot_motion_checker.h"
#include "tests/support/robot_scenes.h"

namespace lmk {
namespace {

// The right arm at shoulder pan `pan` (rad), every other joint at 0: stretched out level at the
// shoulder's height (0.74 m with the torso down), pointing `pan` from straight ahead.
JointValues right_arm(double pan) {
  return {{"r_shoulder_pan_joint", pan},   {"r_shoulder_lift_joint", 0.0},
          {"r_upper_arm_roll_joint", 0.0}, {"r_elbow_flex_joint", 0.0},
          {"r_forearm_roll_joint", 0.0},   {"r_wrist_flex_joint", 0.0},
          {"r_wrist_roll_joint", 0.0}};
}

// The rest of the robot: torso down, left arm raised out of the way.
JointValues rest_of_robot() {
  return {
      {"torso_lift_joint", 0.0}, {"l_shoulder_pan_joint", 1.5}, {"l_shoulder_lift_joint", -0.4}};
}

class MotionCheck : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    body_ = new std::shared_ptr<const RobotBody>(
        std::make_shared<RobotBody>(std::make_shared<RobotModel>(RobotModel::pr2())));
  }
  static void TearDownTestSuite() {
    delete body_;
    body_ = nullptr;
  }
  // The planner's budget is its configurations checked, not the clock: a slow machine or a
  // sanitizer build plans the same path.
  static RobotMotionChecker checker(const PointCloud& scene, const CollisionSceneSettings& s = {}) {
    MotionCheckSettings settings;
    settings.planning_time = 1e6;
    return RobotMotionChecker(*body_, std::make_shared<CollisionScene>(scene, s), kinematics_,
                              rest_of_robot(), settings);
  }
  static inline std::shared_ptr<const RobotBody>* body_ = nullptr;
  static inline const Pr2Kinematics kinematics_{};
};

TEST_F(MotionCheck, AStraightLineThroughABoxIsRefusedAndPlannedAround) {
  // A tall box the arm's sweep from the right to straight ahead passes through.
  const RobotMotionChecker check = checker(test::box_points({0.7, -0.45, 0.74}, {0.1, 0.1, 0.4}));
  const JointValues from = right_arm(-1.2), to = right_arm(0.0);
  const MotionVerdict line = check.check_line(from, to);
  ASSERT_FALSE(line.free());
  EXPECT_EQ(line.contact->obstacle, "the scene");
  EXPECT_EQ(line.contact->link.rfind("r_", 0), 0u) << line.contact->link;
  EXPECT_GT(line.contact->at, 0.0);
  EXPECT_LT(line.contact->at, 1.0);
  EXPECT_LT(line.clearance, check.padding());
  EXPECT_NE(describe(*line.contact).find("the scene"), std::string::npos);
  // Around it: every segment of the plan is free, and it ends at the target.
  const MotionPlan plan = check.plan_around("right_arm", from, to);
  ASSERT_TRUE(plan.found) << plan.message;
  ASSERT_FALSE(plan.waypoints.empty());
  JointValues at = from;
  for (const std::vector<double>& q : plan.waypoints) {
    JointValues next = at;
    for (std::size_t i = 0; i < q.size(); ++i) next[test::right_arm_joint_names()[i]] = q[i];
    const MotionVerdict segment = check.check_line(at, next);
    EXPECT_TRUE(segment.free()) << describe(*segment.contact);
    at = next;
  }
  for (const auto& [name, value] : to)
    EXPECT_NEAR(std::remainder(at[name] - value, 2 * M_PI), 0, 1e-6);
  // Nothing in the way: the straight line is free, with its clearance.
  const MotionVerdict clear =
      checker(test::box_points({0.7, 0.6, 0.74}, {0.1, 0.1, 0.4})).check_line(from, to);
  EXPECT_TRUE(clear.free());
  EXPECT_GT(clear.clearance, 0.02);
}

// A frame from a camera above and behind the shoulders, pitched down, that sees one plate hanging
// above the arm's reach: behind the plate it cannot see.
PointCloud plate_seen_from_above() {
  const int width = 200, height = 160;
  const double f = 150.0, pitch = 35.0 * M_PI / 180.0;
  Eigen::Matrix3d R;  // columns: the optical frame's x, y, z in the base frame
  const Eigen::Vector3d z(std::cos(pitch), 0.0, -std::sin(pitch)), x(0.0, -1.0, 0.0);
  R << x, z.cross(x), z;
  Eigen::Isometry3d T_base_sensor = Eigen::Isometry3d::Identity();
  T_base_sensor.linear() = R;
  T_base_sensor.translation() = Eigen::Vector3d(-0.2, 0.0, 1.6);
  PointCloud cloud;
  cloud.width = width;
  cloud.height = height;
  cloud.T_cloud_sensor = T_base_sensor;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const Eigen::Vector3d ray =
          R * Eigen::Vector3d((u - width / 2.0) / f, (v - height / 2.0) / f, 1.0);
      const double t = (0.5 - T_base_sensor.translation().x()) / ray.x();
      const Eigen::Vector3d p = T_base_sensor.translation() + t * ray;
      const bool on_plate = t > 0 && p.y() > -0.35 && p.y() < 0.1 && p.z() > 0.95 && p.z() < 1.3;
      cloud.points.push_back(on_plate ? p.cast<float>() : Eigen::Vector3f(nan, nan, nan));
    }
  }
  return cloud;
}

TEST_F(MotionCheck, HiddenSpaceBlocksWhenItCountsAsOccupiedAndNotWhenFree) {
  const PointCloud frame = plate_seen_from_above();
  const JointValues from = right_arm(-1.2), to = right_arm(0.0);
  // Stretched straight ahead, the forearm and hand lie in the plate's shadow.
  const MotionVerdict hidden = checker(frame).check_line(from, to);
  ASSERT_FALSE(hidden.free());
  EXPECT_EQ(hidden.contact->obstacle, "space the sensor could not see");
  CollisionSceneSettings free_unknown;
  free_unknown.unknown_is_occupied = false;
  const MotionVerdict seen_only = checker(frame, free_unknown).check_line(from, to);
  EXPECT_TRUE(seen_only.free()) << describe(*seen_only.contact);
}

TEST_F(MotionCheck, AMotionThatStartsNearASurfaceMayNotRunAlongIt) {
  // A plate under the stretched arm's whole sweep, raised until the arm passes 1 cm above it: the
  // pan turns the arm about the vertical, so it keeps that distance all the way.
  const JointValues from = right_arm(-0.5), to = right_arm(0.5);
  const auto plate_at = [](double top) {
    return test::box_points({0.55, 0.0, top - 0.005}, {0.9, 1.4, 0.01});
  };
  CollisionSceneSettings seen_only;  // the plate's points only: no frame, no hidden space
  double top = 0.5;
  double clearance = checker(plate_at(top), seen_only).check_line(from, to).clearance;
  for (int k = 0; k < 8 && !(clearance > 0.007 && clearance < 0.013); ++k) {
    top += clearance - 0.01;
    clearance = checker(plate_at(top), seen_only).check_line(from, to).clearance;
  }
  ASSERT_GT(clearance, 0.007);
  ASSERT_LT(clearance, 0.013);
  // Both ends within the padding of the plate, as demonstrated: near them the arm may stay that
  // close, but not for a 1 m sweep along it.
  const MotionVerdict along = checker(plate_at(top), seen_only).check_line(from, to);
  ASSERT_FALSE(along.free());
  EXPECT_EQ(along.contact->obstacle, "the scene");
  EXPECT_GT(along.contact->at, 0.0);
  EXPECT_LT(along.contact->at, 0.5);
  // A short turn stays within the ends' zones: it is free.
  EXPECT_TRUE(checker(plate_at(top), seen_only).check_line(from, right_arm(-0.48)).free());
}

// The plate's camera turned `yaw` (rad) about the vertical: a second frame, looking elsewhere.
PointCloud turned(PointCloud frame, double yaw) {
  const Eigen::Isometry3d turn(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  for (Eigen::Vector3f& p : frame.points) p = (turn * p.cast<double>()).cast<float>();
  frame.T_cloud_sensor = turn * frame.T_cloud_sensor;
  return frame;
}

TEST_F(MotionCheck, WhereTheArmGoesOutOfEveryViewIsSaidAndBlocksOnlyWhenItCountsAsOccupied) {
  const PointCloud ahead = plate_seen_from_above();
  // From the right (pan -1.2 rad, out of the view's 67 degrees) to straight ahead (in view).
  const JointValues from = right_arm(-1.2), to = right_arm(0.0);
  const RobotMotionChecker one_view = checker(ahead);
  const std::vector<Eigen::Vector3d> unseen = one_view.unseen_along({from, to});
  ASSERT_FALSE(unseen.empty());
  // In the order the arm gets there: the first at the start, on the right.
  EXPECT_LT(unseen.front().y(), -0.4) << unseen.front().transpose();
  EXPECT_TRUE(one_view.unseen_along({to}).empty());
  // Unseen space counts as free by default: with the plate's shadow free too, the line is free;
  // with unseen space occupied, it is refused.
  CollisionSceneSettings shadow_free;
  shadow_free.unknown_is_occupied = false;
  EXPECT_TRUE(checker(ahead, shadow_free).check_line(from, to).free());
  CollisionSceneSettings strict = shadow_free;
  strict.unseen_is_occupied = true;
  const MotionVerdict refused = checker(ahead, strict).check_line(from, to);
  ASSERT_FALSE(refused.free());
  EXPECT_EQ(refused.contact->obstacle, "space no camera has seen");
  // A second frame turned to the right sees where the arm starts: fewer places stay unseen, none
  // of them where the first was.
  const PointCloud right = turned(ahead, -1.0);
  MotionCheckSettings settings;
  const RobotMotionChecker two_views(
      *body_, std::make_shared<CollisionScene>(std::vector<const PointCloud*>{&ahead, &right}),
      kinematics_, rest_of_robot(), settings);
  const std::vector<Eigen::Vector3d> still = two_views.unseen_along({from, to});
  EXPECT_LT(still.size(), unseen.size());
  for (const Eigen::Vector3d& p : still) EXPECT_GT((p - unseen.front()).norm(), 0.04);
}

TEST_F(MotionCheck, AnObjectTheGripperMeansToTouchDoesNotBlockIt) {
  // A 5 cm cube where the closed fingers end up, straight ahead.
  const Eigen::Isometry3d tool =
      kinematics_.T_base_torso() * RobotModel::pr2()
                                       .chain("torso_lift_link", "r_gripper_tool_frame")
                                       .forward(std::vector<double>(7, 0.0));
  const RobotMotionChecker check =
      checker(test::box_points(tool.translation(), {0.05, 0.05, 0.05}));
  const JointValues from = right_arm(-0.4), to = right_arm(0.0);
  const MotionVerdict blind = check.check_line(from, to);
  ASSERT_FALSE(blind.free());
  EXPECT_NE(blind.contact->link.find("gripper"), std::string::npos) << blind.contact->link;
  IntendedContact grasp;
  grasp.near = {tool.translation()};
  grasp.radius = 0.06;
  const MotionVerdict meant = check.check_line(from, to, grasp);
  EXPECT_TRUE(meant.free()) << describe(*meant.contact);
}

}  // namespace
}  // namespace lmk
