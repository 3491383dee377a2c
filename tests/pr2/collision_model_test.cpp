// SPDX-License-Identifier: BSD-3-Clause
// The PR2's collision model (issue #60): lmk's own shapes on every link that moves or stands in
// an arm's way, a self-collision of the elbow with the torso, and agreement with the full PR2
// description's meshes (../shared/data/robots/pr2) on which configurations near a table touch it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include "lmk/geometry/random.h"
#include "lmk/pr2/robot_body.h"
#include "lmk/pr2/robot_model.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

const char* const kRightArm[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint", "r_elbow_flex_joint",
    "r_forearm_roll_joint", "r_wrist_flex_joint",    "r_wrist_roll_joint"};

TEST(CollisionModel, ThePr2HasShapesOnItsArmsTorsoHeadAndBase) {
  std::set<std::string> links;
  for (const LinkSolid& s : RobotModel::pr2().collision_solids()) links.insert(s.link);
  for (const char* side : {"r_", "l_"}) {
    for (const char* link :
         {"shoulder_pan_link", "shoulder_lift_link", "upper_arm_link", "elbow_flex_link",
          "forearm_link", "wrist_flex_link", "gripper_palm_link"}) {
      EXPECT_TRUE(links.count(side + std::string(link))) << side << link;
    }
  }
  for (const char* link : {"base_link", "torso_lift_link", "head_pan_link", "head_tilt_link"})
    EXPECT_TRUE(links.count(link)) << link;
}

// Stretched forward, the arms touch nothing; the right elbow folded back against the torso's
// side touches it, and the contact names both.
TEST(CollisionModel, TheElbowFoldedIntoTheTorsoIsASelfCollision) {
  const RobotBody body(std::make_shared<RobotModel>(RobotModel::pr2()));
  const std::vector<char> right = [&] {
    std::vector<char> moving(body.links().size(), 0);
    for (const char* j : kRightArm) {
      const std::vector<char> m = body.links_moved_by(j);
      for (std::size_t i = 0; i < m.size(); ++i) moving[i] |= m[i];
    }
    return moving;
  }();
  JointValues stretched = {{"torso_lift_joint", 0.1}};
  EXPECT_FALSE(body.self_contact(body.place(stretched), right, 0.02).has_value());
  // The upper arm turned back along the torso (pan -130 degrees) and lowered: the elbow meets the
  // torso's side.
  JointValues folded = stretched;
  folded["r_shoulder_pan_joint"] = -2.28;
  folded["r_shoulder_lift_joint"] = 0.9;
  const std::optional<MotionContact> contact = body.self_contact(body.place(folded), right, 0.02);
  ASSERT_TRUE(contact.has_value());
  EXPECT_LT(contact->distance, 0.02);
  EXPECT_EQ(contact->obstacle.rfind("the robot's ", 0), 0u) << contact->obstacle;
  EXPECT_NE(contact->link.find("r_"), std::string::npos) << contact->link;
}

// The closest approach of a body's moving solids to a table (a box, root frame), from the
// solids' surfaces (spheres: their centres and radii).
// Stops at the first below `enough`: a verdict needs no more.
double table_distance(const std::vector<LinkSolid>& solids,
                      const std::map<std::string, Eigen::Isometry3d>& poses,
                      const std::set<std::string>& moving, const Solid& table,
                      const Eigen::Isometry3d& T_root_table, double enough) {
  const Eigen::Isometry3d T_table_root = T_root_table.inverse();
  double nearest = 1e9;
  for (const LinkSolid& s : solids) {
    if (!moving.count(s.link)) continue;
    const Eigen::Isometry3d T = T_table_root * poses.at(s.link) * s.T_link_solid;
    if (s.solid.kind() == Solid::Kind::sphere) {
      nearest = std::min(nearest, table.signed_distance(T.translation()) - s.solid.size().x());
    } else {
      for (const Eigen::Vector3d& p : s.solid.surface_points(0.005))
        nearest = std::min(nearest, table.signed_distance(T * p));
    }
    if (nearest < enough) break;
  }
  return nearest;
}

// The links the right arm's joints move, by name.
std::set<std::string> right_arm_links(const RobotModel& model) {
  const std::map<std::string, Eigen::Isometry3d> still = model.link_poses({});
  JointValues turned;
  for (const char* j : kRightArm) turned[j] = 0.3;
  std::set<std::string> out;
  for (const auto& [link, pose] : model.link_poses(turned))
    if (!pose.isApprox(still.at(link), 1e-9)) out.insert(link);
  return out;
}

// Issue #60's acceptance: from 1,000 random right-arm configurations with the gripper near a
// table, lmk's shapes and the full description's meshes agree on touching the table or not at a
// 1 cm padding at least 99 times in 100.
TEST(CollisionModel, AgreesWithTheFullDescriptionsMeshesNearATable) {
  LMK_REQUIRE_SHARED_DATA(data);
  const std::string urdf = (data / "robots" / "pr2" / "robot.urdf").string();
  const RobotModel full = RobotModel::from_file(urdf);
  const RobotModel ours = RobotModel::pr2();
  const std::set<std::string> full_arm = right_arm_links(full), our_arm = right_arm_links(ours);
  CollisionShapeSettings fine;
  fine.mesh_cell = 0.002;  // spheres reach at most 1.7 mm beyond the meshes
  fine.only_links.assign(full_arm.begin(), full_arm.end());
  const std::vector<LinkSolid> full_solids = full.collision_solids(fine);
  const std::vector<LinkSolid> our_solids = ours.collision_solids();
  // A table top 5 cm thick at 0.72 m, in front of the robot (root frame: base_footprint).
  const Solid table = Solid::box({1.0, 1.6, 0.05});
  const Eigen::Isometry3d T_root_table(Eigen::Translation3d(0.95, 0.0, 0.745));
  const double padding = 0.01;
  SplitMix64 rng(60);
  const KinematicChain arm = ours.chain("torso_lift_link", "r_gripper_tool_frame");
  int agree = 0, tried = 0, touching = 0;
  while (tried < 1000) {
    const std::vector<double> q = arm.random_joints(rng);
    JointValues joints = {{"torso_lift_joint", 0.1}, {"l_shoulder_lift_joint", -0.5}};
    for (std::size_t i = 0; i < q.size(); ++i) joints[kRightArm[i]] = q[i];
    // Near the table: the tool frame within 25 cm of its top, above it.
    const Eigen::Vector3d tool = ours.link_poses(joints).at("r_gripper_tool_frame").translation();
    const Eigen::Vector3d in_table = T_root_table.inverse() * tool;
    if (std::abs(in_table.x()) > 0.5 || std::abs(in_table.y()) > 0.8 ||
        std::abs(in_table.z()) > 0.25)
      continue;
    ++tried;
    const bool full_touches = table_distance(full_solids, full.link_poses(joints), full_arm, table,
                                             T_root_table, padding) < padding;
    const bool ours_touches = table_distance(our_solids, ours.link_poses(joints), our_arm, table,
                                             T_root_table, padding) < padding;
    agree += full_touches == ours_touches;
    touching += full_touches;
  }
  std::printf("agreement %d of %d (%d touching by the meshes)\n", agree, tried, touching);
  EXPECT_GE(agree, 990);
  // Both verdicts occur: the sample tells something.
  EXPECT_GT(touching, 100);
  EXPECT_LT(touching, 900);
}

}  // namespace
}  // namespace lmk
