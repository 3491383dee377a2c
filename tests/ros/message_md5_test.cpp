// SPDX-License-Identifier: BSD-3-Clause
// The robot's action messages are defined in lmk (Debian ships neither pr2_controllers_msgs nor
// control_msgs), so their md5sums must equal those the robot's own packages publish: otherwise
// roscpp refuses the connection and no goal ever reaches the controllers. The expected sums are the
// published ones, as the generated code of pr2_controllers_msgs 1.10 and control_msgs 1.5 declares
// them (e.g. rosserial's ros_lib headers); lmk computes its own from ros/msg with gencpp.
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <gtest/gtest.h>
#include <pr2_controllers_msgs/JointTrajectoryAction.h>
#include <pr2_controllers_msgs/PointHeadAction.h>
#include <pr2_controllers_msgs/Pr2GripperCommandAction.h>
#include <ros/message_traits.h>

#include <string>

namespace {

template <class Message>
std::string md5() {
  return ros::message_traits::md5sum<Message>();
}

template <class Message>
std::string type() {
  return ros::message_traits::datatype<Message>();
}

TEST(MessageMd5, Pr2ArmTrajectoryActionMatchesThePr2) {
  using namespace pr2_controllers_msgs;
  EXPECT_EQ(type<JointTrajectoryActionGoal>(), "pr2_controllers_msgs/JointTrajectoryActionGoal");
  EXPECT_EQ(md5<JointTrajectoryActionGoal>(), "a99e83ef6185f9fdd7693efe99623a86");
  EXPECT_EQ(md5<JointTrajectoryActionResult>(), "1eb06eeff08fa7ea874431638cb52332");
  EXPECT_EQ(md5<JointTrajectoryActionFeedback>(), "aae20e09065c3809e8a8e87c4c8953fd");
}

TEST(MessageMd5, Pr2GripperActionMatchesThePr2) {
  using namespace pr2_controllers_msgs;
  EXPECT_EQ(md5<Pr2GripperCommand>(), "680acaff79486f017132a7f198d40f08");
  EXPECT_EQ(md5<Pr2GripperCommandActionGoal>(), "aa581f648a35ed681db2ec0bf7a82bea");
  EXPECT_EQ(md5<Pr2GripperCommandActionResult>(), "143702cb2df0f163c5283cedc5efc6b6");
  EXPECT_EQ(md5<Pr2GripperCommandActionFeedback>(), "653dff30c045f5e6ff3feb3409f4558d");
}

TEST(MessageMd5, Pr2PointHeadActionMatchesThePr2) {
  using namespace pr2_controllers_msgs;
  EXPECT_EQ(md5<PointHeadActionGoal>(), "b53a8323d0ba7b310ba17a2d3a82a6b8");
  EXPECT_EQ(md5<PointHeadActionResult>(), "1eb06eeff08fa7ea874431638cb52332");
  EXPECT_EQ(md5<PointHeadActionFeedback>(), "33c9244957176bbba97dd641119e8460");
}

TEST(MessageMd5, FollowJointTrajectoryMatchesControlMsgs) {
  using namespace control_msgs;
  EXPECT_EQ(type<FollowJointTrajectoryActionGoal>(),
            "control_msgs/FollowJointTrajectoryActionGoal");
  EXPECT_EQ(md5<FollowJointTrajectoryActionGoal>(), "cff5c1d533bf2f82dd0138d57f4304bb");
  EXPECT_EQ(md5<FollowJointTrajectoryActionResult>(), "c4fb3b000dc9da4fd99699380efcc5d9");
  EXPECT_EQ(md5<FollowJointTrajectoryActionFeedback>(), "d8920dc4eae9fc107e00999cce4be641");
  EXPECT_EQ(md5<FollowJointTrajectoryResult>(), "493383b18409bfb604b4e26c676401d2");
}

}  // namespace
