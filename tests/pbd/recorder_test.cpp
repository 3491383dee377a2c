// SPDX-License-Identifier: BSD-3-Clause
// Recording: each arm is attached to the nearest landmark instance within the distance, otherwise
// to the base, and changing a step's frame afterwards keeps the tool where it was.

#include "lmk/pbd/recorder.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/pbd/plan.h"

namespace lmk {
namespace {

Box box_at(const Eigen::Vector3d& centre, double yaw, const Eigen::Vector3d& size) {
  return Box(pose_from_xyz_rpy(centre, {0, 0, yaw}), size);
}

Recorder demo_recorder(double max_distance = 0.3) {
  std::vector<LandmarkInstance> instances = {
      {"bowl", box_at({0.6, 0.2, 0.75}, 0.4, {0.16, 0.16, 0.08})},
      {"bowl", box_at({0.6, -0.3, 0.75}, -0.2, {0.16, 0.16, 0.08})},
      {"shelf", box_at({1.2, 0.0, 1.0}, 0.0, {0.3, 0.8, 0.05})},
  };
  RecorderSettings settings;
  settings.max_distance = max_distance;
  return Recorder("pick", {{"bowl", "bowl.lmk"}, {"shelf", "shelf.lmk"}}, instances, settings);
}

ArmState tool_at(const Eigen::Vector3d& p, GripperAction g = GripperAction::kOpen) {
  return {pose_from_xyz_rpy(p, {0.1, 0.5, -0.3}), g};
}

TEST(DistanceToBox, IsZeroInsideAndToTheNearestFaceOutside) {
  const Box b = box_at({1, 0, 0}, 0.5, {0.2, 0.4, 0.6});
  EXPECT_DOUBLE_EQ(distance_to_box({1, 0, 0}, b), 0.0);
  // 0.1 m above the top face, which is 0.3 m above the centre.
  EXPECT_NEAR(distance_to_box({1, 0, 0.4}, b), 0.1, 1e-12);
  // Beyond a corner: the distance to the corner, here in the box's own axes.
  const Eigen::Vector3d corner = b.pose * Eigen::Vector3d(0.1, 0.2, 0.3);
  const Eigen::Vector3d out = b.pose * Eigen::Vector3d(0.13, 0.24, 0.3);
  EXPECT_NEAR(distance_to_box(out, b), (out - corner).norm(), 1e-12);
}

TEST(Recorder, AttachesEachArmToTheNearestInstanceWithinTheDistance) {
  Recorder r = demo_recorder();
  // Left tool 5 cm above the second bowl; right tool far from everything.
  const ArmState left = tool_at({0.6, -0.3, 0.84}, GripperAction::kClose);
  const ArmState right = tool_at({0.1, 0.9, 1.5});
  const std::size_t step = r.save_pose(left, right, 3.0);
  const ProgramStep& s = r.program().steps.at(step);
  ASSERT_TRUE(s.left && s.right);
  EXPECT_EQ(s.left->frame, "bowl");
  EXPECT_EQ(s.left->gripper, GripperAction::kClose);
  EXPECT_EQ(s.right->frame, kBaseFrame);
  EXPECT_EQ(s.duration, 3.0);
  // Relative to the second bowl, not the first: composing with its pose gives the tool back.
  const Box& second = r.instances()[1].box;
  EXPECT_TRUE((second.pose * s.left->T_frame_ee).isApprox(left.T_base_ee, 1e-12));
  EXPECT_TRUE(s.right->T_frame_ee.isApprox(right.T_base_ee, 1e-12));
}

TEST(Recorder, BeyondTheDistanceTheBaseFrameIsUsed) {
  // 20 cm above the first bowl's top face: attached at 0.3 m, not at 0.1 m.
  const ArmState tool = tool_at({0.6, 0.2, 0.99});
  Recorder near = demo_recorder(0.3);
  Recorder far = demo_recorder(0.1);
  near.save_pose(tool, std::nullopt);
  far.save_pose(tool, std::nullopt);
  EXPECT_EQ(near.program().steps[0].left->frame, "bowl");
  EXPECT_EQ(far.program().steps[0].left->frame, kBaseFrame);
  EXPECT_FALSE(near.program().steps[0].right.has_value());
}

TEST(Recorder, ChangingTheFrameKeepsTheBasePose) {
  Recorder r = demo_recorder();
  const ArmState tool = tool_at({0.62, 0.18, 0.8});
  r.save_pose(std::nullopt, tool);
  ASSERT_EQ(r.program().steps[0].right->frame, "bowl");
  for (const char* frame : {"shelf", kBaseFrame, "bowl"}) {
    r.set_frame(0, Arm::kRight, frame);
    EXPECT_EQ(r.program().steps[0].right->frame, frame);
    EXPECT_TRUE(r.base_pose(0, Arm::kRight).isApprox(tool.T_base_ee, 1e-12)) << frame;
  }
  // In the shelf's frame the stored pose is the shelf-relative one.
  r.set_frame(0, Arm::kRight, "shelf");
  const Box& shelf = r.instances()[2].box;
  EXPECT_TRUE(r.program().steps[0].right->T_frame_ee.isApprox(shelf.pose.inverse() * tool.T_base_ee,
                                                              1e-12));
}

// The program remembers where each landmark was in the demonstration: the instance its steps were
// recorded against, which symmetric landmarks and the demonstration-based policies need.
TEST(Recorder, RemembersTheDemonstratedInstanceOfEachLandmark) {
  Recorder r = demo_recorder();
  const auto demonstration = [&r](const char* name) {
    return *r.program().landmark(name)->demonstration;
  };
  // Before any step: each landmark's first instance in the scene.
  EXPECT_TRUE(demonstration("bowl").isApprox(r.instances()[0].box.pose, 1e-12));
  EXPECT_TRUE(demonstration("shelf").isApprox(r.instances()[2].box.pose, 1e-12));
  // A step at the second bowl makes it the demonstrated one; moving that step to the base frame
  // falls back to the first.
  r.save_pose(tool_at({0.6, -0.3, 0.84}), std::nullopt);
  EXPECT_TRUE(demonstration("bowl").isApprox(r.instances()[1].box.pose, 1e-12));
  r.set_frame(0, Arm::kLeft, kBaseFrame);
  EXPECT_TRUE(demonstration("bowl").isApprox(r.instances()[0].box.pose, 1e-12));
  // A symmetric landmark without any instance cannot be recorded: it would have no orientation
  // to turn its matches to.
  ProgramLandmark rim("rim", "rim.lmk");
  rim.symmetry = Symmetry{Eigen::Vector3d::UnitZ(), 0};
  EXPECT_THROW(Recorder("p", {rim}, {}), Error);
  EXPECT_NO_THROW(Recorder("p", {rim}, {{"rim", box_at({0.7, 0, 0.8}, 0, {0.2, 0.2, 0.05})}}));
}

TEST(Recorder, RefusesWhatItCannotRecord) {
  Recorder r = demo_recorder();
  EXPECT_THROW(r.save_pose(std::nullopt, std::nullopt), Error);
  r.save_pose(tool_at({0.6, 0.2, 0.8}), std::nullopt);
  EXPECT_THROW(r.set_frame(0, Arm::kRight, "bowl"), Error);  // the step has no right arm
  EXPECT_THROW(r.set_frame(3, Arm::kLeft, "bowl"), Error);   // no such step
  EXPECT_THROW(r.set_frame(0, Arm::kLeft, "cup"), Error);    // not a program landmark
  // A declared landmark with no instance in the demonstration scene.
  Recorder empty("p", {{"bowl", "bowl.lmk"}}, {});
  empty.save_pose(tool_at({0.6, 0.2, 0.8}), std::nullopt);
  EXPECT_EQ(empty.program().steps[0].left->frame, kBaseFrame);
  EXPECT_THROW(empty.set_frame(0, Arm::kLeft, "bowl"), Error);
  // An instance of an undeclared landmark.
  EXPECT_THROW(Recorder("p", {}, {{"bowl", box_at({0, 0, 0}, 0, {0.1, 0.1, 0.1})}}), Error);
}

}  // namespace
}  // namespace lmk

namespace lmk {
namespace {

// Issue #59: a step recorded relative to an instance whose capture check warned says so, at
// record (Recorder::warnings) and at plan (capture_warnings, Plan::warnings); steps relative to
// the base or to a landmark the check passed say nothing.
TEST(Recorder, AStepOnAWarnedLandmarkIsFlaggedAtRecordAndAtPlan) {
  std::vector<LandmarkInstance> instances = {
      {"rack", box_at({0.6, 0.2, 0.75}, 0.0, {0.3, 0.1, 0.1}), {"matches 2 other places"}},
      {"bowl", box_at({0.6, -0.3, 0.75}, 0.0, {0.16, 0.16, 0.08})},
  };
  Recorder r("hang", {{"rack", "rack.lmk"}, {"bowl", "bowl.lmk"}}, instances);
  r.save_pose(tool_at({0.6, -0.3, 0.84}), std::nullopt);             // step 0: the bowl
  r.save_pose(tool_at({0.6, 0.2, 0.85}), tool_at({0.1, 0.9, 1.5}));  // step 1: rack; base
  const std::vector<std::string> recorded = r.warnings();
  ASSERT_EQ(recorded.size(), 1u);
  EXPECT_NE(recorded[0].find("step 1, left arm"), std::string::npos) << recorded[0];
  EXPECT_NE(recorded[0].find("'rack'"), std::string::npos);
  EXPECT_NE(recorded[0].find("matches 2 other places"), std::string::npos);

  std::map<std::string, Landmark> landmarks;
  landmarks["rack"].findings.present = true;
  landmarks["rack"].findings.look_alike_checked = true;
  landmarks["rack"].findings.look_alikes = 2;
  landmarks["bowl"].findings.present = true;  // checked, nothing to warn of
  const std::vector<std::string> planned = capture_warnings(r.program(), landmarks);
  ASSERT_EQ(planned.size(), 1u);
  EXPECT_NE(planned[0].find("landmark 'rack' (step 1)"), std::string::npos) << planned[0];
  EXPECT_NE(planned[0].find("matches 2 other places"), std::string::npos);
}

}  // namespace
}  // namespace lmk
