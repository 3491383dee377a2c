// SPDX-License-Identifier: BSD-3-Clause
// Looking again (look_again.h) on the tests' table: an L that the first view's edge cuts is found
// once the head turns towards it, and an absent one is refused after the allowed looks, each named;
// where the arm would go out of every view is looked at before it goes (issue #60).

#include "lmk/pbd/look_again.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/pr2/pr2_motion_check.h"
#include "tests/pbd/robot_at_table.h"

namespace lmk {
namespace {

using test_scenes::box_at;
using test_scenes::capture_camera;
using test_scenes::kWorldBase;
using test_scenes::scene_in_base;

// A camera fixed where the tests' capture camera stands that turns to look where it is asked,
// seeing the table with L-shapes at `copies`; counts its looks.
class TurningCamera : public Eyes {
 public:
  explicit TurningCamera(std::vector<Eigen::Vector2d> copies) : copies_(std::move(copies)) {}

  PointCloud first() const { return view(capture_camera()); }

  CallResult look_at(const Eigen::Vector3d& target, PointCloud& frame) override {
    ++looks;
    const Eigen::Vector3d eye = capture_camera().translation();
    frame = view(camera_look_at(eye, kWorldBase * target, Eigen::Vector3d::UnitZ()));
    return CallResult::success();
  }
  int looks = 0;

 private:
  PointCloud view(const Eigen::Isometry3d& camera) const {
    return scene_in_base(copies_, false, camera);
  }
  std::vector<Eigen::Vector2d> copies_;
};

class LookAgainTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { landmark_ = new Landmark(test_scenes::demonstrated_l()); }
  static void TearDownTestSuite() { delete landmark_; }

  // Touch the L from above.
  static Program program() {
    Program p;
    p.name = "touch l";
    p.landmarks = {{"l", "l.lmk"}};
    ProgramStep touch;
    touch.right =
        ArmTarget{"l", pose_from_xyz_rpy({0, 0, 0.15}, {0, 0.5 * M_PI, 0}), GripperAction::kOpen};
    p.steps = {touch};
    return p;
  }

  // `unseen_looks` >= 0: motions are checked (lmk's PR2 body), with that many looks where they
  // would go unseen.
  LookedPlan plan_with(TurningCamera& camera, int max_looks, int unseen_looks = -1) const {
    const SimulatedPr2 robot = test_scenes::robot_at_table();
    JointState state;
    EXPECT_TRUE(robot.read_joint_state(state).ok());
    LookAgainSettings looking;
    looking.max_looks = max_looks;
    PlanSettings settings;
    if (unseen_looks >= 0) {
      looking.unseen_looks = unseen_looks;
      // Bounded by configurations checked, not seconds: the same plan under a sanitizer.
      Pr2MotionCheckSettings untimed;
      untimed.motion.planning_time = 1e6;
      settings.motion_checker = pr2_motion_checker(robot.kinematics(), untimed);
    }
    return plan_looking_again(program(), {{"l", *landmark_}}, camera.first(), robot.kinematics(),
                              state, camera, settings, looking);
  }

  static Landmark* landmark_;
};

Landmark* LookAgainTest::landmark_ = nullptr;

// Where the L stands: near the table's right end, where the first view's edge cuts through its box.
const Eigen::Vector2d kAtTheEdge(0.6, -0.3);

TEST_F(LookAgainTest, ALandmarkTheImagesEdgeCutsIsFoundByLookingAgain) {
  TurningCamera camera({kAtTheEdge});
  const LookedPlan once = plan_with(camera, 0);
  ASSERT_FALSE(once.plan.valid()) << "the first view alone should not settle it";
  EXPECT_TRUE(once.looks.empty());
  EXPECT_EQ(camera.looks, 0);

  const LookedPlan looked = plan_with(camera, 2);
  ASSERT_TRUE(looked.plan.valid())
      << describe(*looked.plan.refusal) << " " << describe_looks(looked.looks);
  ASSERT_FALSE(looked.looks.empty());
  EXPECT_EQ(camera.looks, static_cast<int>(looked.looks.size()));
  const LocatedLandmark* l = looked.plan.landmark("l");
  ASSERT_NE(l, nullptr);
  const Eigen::Vector3d truth = box_at(kAtTheEdge).transformed(kWorldBase.inverse()).center();
  EXPECT_LT((l->match.box.center() - truth).norm(), 0.0254);
}

TEST_F(LookAgainTest, AnAbsentLandmarkIsRefusedAfterEveryLookNamingThem) {
  TurningCamera camera({});
  const LookedPlan looked = plan_with(camera, 2);
  ASSERT_FALSE(looked.plan.valid());
  EXPECT_TRUE(std::holds_alternative<LandmarkNotFound>(*looked.plan.refusal))
      << describe(*looked.plan.refusal);
  ASSERT_EQ(looked.looks.size(), 2u);
  EXPECT_EQ(camera.looks, 2);
  const std::string said = describe_looks(looked.looks);
  EXPECT_NE(said.find("after 2 more looks"), std::string::npos) << said;
  EXPECT_NE(said.find("panned +15 degrees"), std::string::npos) << said;
  EXPECT_NE(said.find("panned -15 degrees"), std::string::npos) << said;
  EXPECT_TRUE(looked.plan.steps.empty());
}

TEST_F(LookAgainTest, WhereTheArmWouldGoUnseenIsLookedAtFirst) {
  // The L in the middle of the first view; the arm starts at the robot's side, out of it.
  TurningCamera camera({Eigen::Vector2d(0.3, -0.1)});
  const LookedPlan blind = plan_with(camera, 0, 0);
  ASSERT_TRUE(blind.plan.valid()) << describe(*blind.plan.refusal);
  EXPECT_EQ(camera.looks, 0);
  ASSERT_FALSE(blind.plan.steps.at(0).arms.at(0).unseen.empty());
  const auto warned = std::find_if(
      blind.plan.warnings.begin(), blind.plan.warnings.end(), [](const std::string& w) {
        return w.find("step 0, right arm: passes through space no camera has seen") !=
               std::string::npos;
      });
  EXPECT_NE(warned, blind.plan.warnings.end());

  const LookedPlan looked = plan_with(camera, 0, 2);
  ASSERT_TRUE(looked.plan.valid()) << describe(*looked.plan.refusal);
  ASSERT_FALSE(looked.looks.empty());
  EXPECT_EQ(camera.looks, static_cast<int>(looked.looks.size()));
  EXPECT_NE(looked.looks.front().why.find("step 0's right arm would pass through space no camera"),
            std::string::npos)
      << looked.looks.front().why;
  // The look was where the arm would go unseen: fewer of its places stay unseen.
  EXPECT_LT(looked.plan.steps.at(0).arms.at(0).unseen.size(),
            blind.plan.steps.at(0).arms.at(0).unseen.size());
}

TEST(LookAgainSettings, BadValuesAreRefused) {
  LookAgainSettings s;
  s.max_looks = -1;
  EXPECT_THROW(s.validate(), Error);
  s.max_looks = 2;
  s.pattern_angle = 0.0;
  EXPECT_THROW(s.validate(), Error);
  s.pattern_angle = 0.2;
  s.unseen_looks = 9;
  EXPECT_THROW(s.validate(), Error);
}

}  // namespace
}  // namespace lmk
