// SPDX-License-Identifier: BSD-3-Clause
// What executed trajectories touched (issue #60, trajectory_contacts.h): the right arm swept
// through a box touches it, and not when the box stands aside; the gripper may touch what lies at
// its grasp; the simulated PR2 keeps every contact and still runs the motion.

#include "lmk/pr2/trajectory_contacts.h"

#include <gtest/gtest.h>

#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/pr2/simulated_pr2.h"
#include "tests/support/robot_scenes.h"

namespace lmk {
namespace {

// The right arm stretched out level at the shoulder, pointing `pan` from straight ahead.
std::vector<double> stretched(double pan) { return {pan, 0, 0, 0, 0, 0, 0}; }

JointValues robot_with_right_arm(const std::vector<double>& q) {
  JointValues state = {
      {"torso_lift_joint", 0.0}, {"l_shoulder_pan_joint", 1.5}, {"l_shoulder_lift_joint", -0.4}};
  for (std::size_t i = 0; i < q.size(); ++i) state[test::right_arm_joint_names()[i]] = q[i];
  return state;
}

JointTrajectory right_arm_to(const std::vector<double>& q, double seconds) {
  JointTrajectory t;
  t.joint_names = test::right_arm_joint_names();
  t.points.push_back({q, seconds});
  return t;
}

std::shared_ptr<const CollisionScene> box_world(const Eigen::Vector3d& centre,
                                                const Eigen::Vector3d& size) {
  const test::BoxMesh box = test::box_mesh(centre, size);
  return ground_truth_scene(box.vertices, box.triangles);
}

TEST(TrajectoryContacts, ASweepThroughABoxTouchesItAndNotWhenItStandsAside) {
  const Pr2Kinematics kinematics;
  const JointValues start = robot_with_right_arm(stretched(-1.2));
  const JointTrajectory sweep = right_arm_to(stretched(0.0), 3.0);
  const auto contact = [&](const Eigen::Vector3d& centre) {
    const RobotMotionChecker checker =
        contact_checker(pr2_body(), box_world(centre, {0.1, 0.1, 0.4}), kinematics, start);
    return trajectory_contact(checker, kinematics, "right_arm", start, sweep);
  };
  const std::optional<MotionContact> hit = contact({0.7, -0.45, 0.74});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->link.rfind("r_", 0), 0u) << hit->link;
  EXPECT_EQ(hit->obstacle, "the world");
  EXPECT_LT(hit->distance, 0.0);
  EXPECT_GT(hit->at, 0.0);
  EXPECT_LT(hit->at, 1.0);
  EXPECT_NE(describe_touch(*hit).find("into the world near ("), std::string::npos);
  EXPECT_FALSE(contact({0.7, 0.6, 0.74}));
}

TEST(TrajectoryContacts, TheGripperMayTouchWhatLiesAtItsTarget) {
  const Pr2Kinematics kinematics;
  const JointValues start = robot_with_right_arm(stretched(-1.2));
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(kinematics.forward("right_arm", stretched(0.0), tool).ok());
  // A small box at the tool frame where the sweep ends: the fingers close on it.
  const auto at_grasp = box_world(tool.translation(), {0.04, 0.04, 0.04});
  const RobotMotionChecker checker = contact_checker(pr2_body(), at_grasp, kinematics, start);
  EXPECT_FALSE(trajectory_contact(checker, kinematics, "right_arm", start,
                                  right_arm_to(stretched(0.0), 3.0)));
  // Without the grasp's allowance it is a contact.
  TrajectoryContactSettings strict;
  strict.intended_radius = 0.0;
  EXPECT_TRUE(trajectory_contact(checker, kinematics, "right_arm", start,
                                 right_arm_to(stretched(0.0), 3.0), strict));
}

TEST(TrajectoryContacts, TheSimulatedPr2KeepsEveryContactAndStillMoves) {
  SimulatedPr2 robot;
  ASSERT_TRUE(robot.configure().ok());
  ASSERT_TRUE(robot.activate().ok());
  // A box around where the upper arm ends, stretched straight ahead.
  const auto world = box_world({0.2, -0.19, 0.74}, {0.1, 0.1, 0.1});
  int asked = 0;
  robot.contact_world = [&] {
    ++asked;
    return world;
  };
  ASSERT_TRUE(robot.send_trajectory("right_arm", right_arm_to(stretched(0.0), 4.0)).ok());
  EXPECT_EQ(asked, 1);
  ASSERT_EQ(robot.contacts().size(), 1u);
  EXPECT_EQ(robot.contacts()[0].motion, 0u);
  EXPECT_EQ(robot.contacts()[0].group, "right_arm");
  EXPECT_EQ(robot.group_positions("right_arm"), stretched(0.0));  // it ran: nothing stops it
  // Back out of the box and further away: the way out starts inside, so it touches too; the
  // next motion, clear of it, does not.
  ASSERT_TRUE(robot.send_trajectory("right_arm", right_arm_to(stretched(-1.0), 4.0)).ok());
  ASSERT_TRUE(robot.send_trajectory("right_arm", right_arm_to(stretched(-1.5), 4.0)).ok());
  ASSERT_EQ(robot.contacts().size(), 2u);
  EXPECT_EQ(robot.contacts()[1].motion, 1u);
}

}  // namespace
}  // namespace lmk
