// SPDX-License-Identifier: BSD-3-Clause
// Programs that watch (watch.h, issue #48) on the tests' table: the simulated PR2 reaches for an
// L-shape that a person pushes 5 cm once the arm is on its way. Watching, the executor notices the
// push before the gripper closes and re-plans to the L's new place (or stops, as asked); without
// watching, the arm closes where the L was.

#include "lmk/pbd/watch.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "tests/pbd/robot_at_table.h"

namespace lmk {
namespace {

using test_scenes::box_at;
using test_scenes::kWorldBase;
using test_scenes::scene_in_base;

const Eigen::Vector2d kDemo(-0.1, -0.15);

// The simulated PR2 the tests drive: the first base of PushedWhileReaching, so that it is built
// before the robot that forwards to it.
struct AtTheTable {
  SimulatedPr2 pr2 = test_scenes::robot_at_table();
};

// The simulated PR2, and a person who moves the L once the arm's first trajectory has run.
class PushedWhileReaching : private AtTheTable, public ForwardingRobot {
 public:
  explicit PushedWhileReaching(std::optional<Eigen::Vector2d> pushed_to)
      : ForwardingRobot(pr2), pushed_to_(pushed_to) {}

  // What the head camera sees now: the table with the L where it stands (none once taken).
  CallResult frame(PointCloud& out) const {
    out = scene_in_base(
        where_ ? std::vector<Eigen::Vector2d>{*where_} : std::vector<Eigen::Vector2d>{}, false);
    return CallResult::success();
  }

  CallResult send_trajectory(const std::string& group, const JointTrajectory& t) override {
    const CallResult r = ForwardingRobot::send_trajectory(group, t);
    if (++trajectories == 1) where_ = pushed_to_;  // pushed (or taken) as the arm gets there
    return r;
  }

  const Pr2Kinematics& kinematics() const { return pr2.kinematics(); }
  // Where the right tool is now, base frame.
  Eigen::Isometry3d tool() const {
    JointState s;
    EXPECT_TRUE(pr2.read_joint_state(s).ok());
    const GroupInfo group = *pr2.kinematics().group("right_arm");
    std::vector<double> q;
    for (const JointInfo& j : group.joints) {
      for (std::size_t i = 0; i < s.names.size(); ++i)
        if (s.names[i] == j.name) q.push_back(s.positions[i]);
    }
    Eigen::Isometry3d T;
    EXPECT_TRUE(pr2.kinematics().forward("right_arm", q, T).ok());
    return T;
  }
  int trajectories = 0;

 private:
  std::optional<Eigen::Vector2d> where_ = kDemo;
  std::optional<Eigen::Vector2d> pushed_to_;
};

// The centimetres a line says the L moved ("'l' moved 4.8 cm, ..."), or -1.
double centimetres_moved(const std::string& line) {
  const std::size_t at = line.find("'l' moved ");
  return at == std::string::npos ? -1.0 : std::stod(line.substr(at + 10));
}

class WatchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { landmark_ = new Landmark(test_scenes::demonstrated_l()); }
  static void TearDownTestSuite() { delete landmark_; }

  // Above the L, then down to it and close: two steps relative to it.
  static const Eigen::Isometry3d& grasp() {
    static const Eigen::Isometry3d T = pose_from_xyz_rpy({0, 0, 0.12}, {0, 0.5 * M_PI, 0});
    return T;
  }
  static Program program() {
    Program p;
    p.name = "take l";
    p.landmarks = {{"l", "l.lmk"}};
    ProgramStep above, take;
    above.right =
        ArmTarget{"l", pose_from_xyz_rpy({0, 0, 0.2}, {0, 0.5 * M_PI, 0}), GripperAction::kOpen};
    take.right = ArmTarget{"l", grasp(), GripperAction::kClose};
    p.steps = {above, take};
    return p;
  }

  static Plan planned(PushedWhileReaching& robot) {
    JointState state;
    EXPECT_TRUE(robot.read_joint_state(state).ok());
    PointCloud first;
    EXPECT_TRUE(robot.frame(first).ok());
    Plan p = plan(program(), {{"l", *landmark_}}, first, robot.kinematics(), state);
    EXPECT_TRUE(p.valid()) << describe(*p.refusal);
    return p;
  }

  static WatchedExecution run(PushedWhileReaching& robot, const WatchSettings& watching) {
    const Plan p = planned(robot);
    TrackingWatch watch(p, {{"l", *landmark_}},
                        [&robot](PointCloud& frame) { return robot.frame(frame); });
    return execute_watching(program(), p, robot, robot.kinematics(), watch, watching);
  }

  // Where the grasp is for the L standing at `xy`, base frame.
  static Eigen::Vector3d grasp_at(const Eigen::Vector2d& xy) {
    return (box_at(xy).transformed(kWorldBase.inverse()).pose * grasp()).translation();
  }

  static Landmark* landmark_;
};

Landmark* WatchTest::landmark_ = nullptr;

// Pushed 5 cm along the table, away from the robot.
const Eigen::Vector2d kPushed = kDemo + Eigen::Vector2d(0.05, 0.0);

TEST_F(WatchTest, APushedLandmarkIsNoticedAndTheRestOfTheProgramReplannedToItsNewPlace) {
  PushedWhileReaching robot(kPushed);
  const WatchedExecution done = run(robot, {});
  ASSERT_TRUE(done.report.completed) << done.report.error;
  EXPECT_EQ(done.replans, 1u);
  ASSERT_EQ(done.noticed.size(), 1u);
  EXPECT_EQ(done.noticed[0].rfind("before step 0's gripper: 'l' moved ", 0), 0u) << done.noticed[0];
  EXPECT_NEAR(centimetres_moved(done.noticed[0]), 5.0, 0.5) << done.noticed[0];
  // The hand closed at the L's new place, not its old one.
  const Eigen::Vector3d hand = robot.tool().translation();
  EXPECT_LT((hand - grasp_at(kPushed)).norm(), 0.01);
  EXPECT_GT((hand - grasp_at(kDemo)).norm(), 0.04);
}

TEST_F(WatchTest, ALandmarkLeftWhereItWasIsWatchedWithoutAReplan) {
  PushedWhileReaching robot(kDemo);
  const WatchedExecution done = run(robot, {});
  ASSERT_TRUE(done.report.completed) << done.report.error;
  EXPECT_EQ(done.replans, 0u);
  EXPECT_TRUE(done.noticed.empty()) << done.noticed.front();
  EXPECT_LT((robot.tool().translation() - grasp_at(kDemo)).norm(), 0.01);
}

TEST_F(WatchTest, WithoutWatchingTheArmClosesWhereTheLandmarkWas) {
  PushedWhileReaching robot(kPushed);
  const ExecutionReport report = execute(planned(robot), robot);
  ASSERT_TRUE(report.completed) << report.error;
  const Eigen::Vector3d hand = robot.tool().translation();
  EXPECT_LT((hand - grasp_at(kDemo)).norm(), 0.01);  // today's open loop: where it was found
}

TEST_F(WatchTest, AskedToStopOnAMoveItStopsBeforeTheGripperMoves) {
  PushedWhileReaching robot(kPushed);
  WatchSettings watching;
  watching.when_moved = WhenMoved::kStop;
  const WatchedExecution done = run(robot, watching);
  EXPECT_FALSE(done.report.completed);
  EXPECT_EQ(done.report.steps_completed, 0u);
  EXPECT_NEAR(centimetres_moved(done.report.error), 5.0, 0.5) << done.report.error;
  EXPECT_NE(done.report.error.find("stopped"), std::string::npos) << done.report.error;
  EXPECT_EQ(robot.trajectories, 1);  // the approach only: nothing sent towards the old pose after
  for (const std::string& line : done.report.log)
    EXPECT_EQ(line.find("gripper"), std::string::npos) << line;
}

TEST_F(WatchTest, AProgramThatSaysStopIsStoppedWhateverTheSettings) {
  PushedWhileReaching robot(kPushed);
  Program says_stop = program();
  says_stop.when_landmark_moves = WhenMoved::kStop;
  const Plan p = planned(robot);
  TrackingWatch watch(p, {{"l", *landmark_}},
                      [&robot](PointCloud& frame) { return robot.frame(frame); });
  const WatchedExecution done =
      execute_watching(says_stop, p, robot, robot.kinematics(), watch, {});  // default: re-plan
  EXPECT_FALSE(done.report.completed);
  EXPECT_EQ(done.replans, 0u);
  EXPECT_NE(done.report.error.find("stopped, as the program asks"), std::string::npos)
      << done.report.error;
}

TEST_F(WatchTest, ALandmarkTakenAwayStopsTheProgram) {
  PushedWhileReaching robot(std::nullopt);
  const WatchedExecution done = run(robot, {});
  EXPECT_FALSE(done.report.completed);
  EXPECT_NE(done.report.error.find("'l' is lost: stopped rather than move towards where it was"),
            std::string::npos)
      << done.report.error;
  EXPECT_EQ(robot.trajectories, 1);
}

// A watch that reports the L wherever the test says, for what rendering cannot show cheaply.
class SaidWatch : public LandmarkWatch {
 public:
  explicit SaidWatch(Eigen::Isometry3d where) : where_(where) {}
  CallResult observe(const std::vector<std::string>&,
                     std::map<std::string, Eigen::Isometry3d>& where) override {
    where["l"] = where_;
    return CallResult::success();
  }

 private:
  Eigen::Isometry3d where_;
};

TEST_F(WatchTest, AReplanOutOfReachStopsBeforeAnyMotion) {
  PushedWhileReaching robot(kDemo);
  const Plan p = planned(robot);
  // Carried 1.5 m off, beyond the arm's reach.
  SaidWatch watch(pose_from_xyz_rpy({1.5, 0, 0}, {0, 0, 0}) * p.landmark("l")->match.box.pose);
  const WatchedExecution done =
      execute_watching(program(), p, robot, robot.kinematics(), watch, {});
  EXPECT_FALSE(done.report.completed);
  EXPECT_NE(done.report.error.find("before step 0: 'l' moved 150.0 cm"), std::string::npos)
      << done.report.error;
  EXPECT_NE(done.report.error.find("unreachable"), std::string::npos) << done.report.error;
  EXPECT_EQ(robot.trajectories, 0);
}

TEST(WatchSettings, BadTolerancesAreRefused) {
  WatchSettings s;
  s.translation_tolerance = 0.0;
  EXPECT_THROW(s.validate(), Error);
  s.translation_tolerance = 0.01;
  s.rotation_tolerance = std::nan("");
  EXPECT_THROW(s.validate(), Error);
}

}  // namespace
}  // namespace lmk
