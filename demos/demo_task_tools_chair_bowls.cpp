// SPDX-License-Identifier: BSD-3-Clause
// Tasks 1-3 of the paper's PbD demonstrations: hanging tools, grasping a chair, picking bowls from
// a shelf. Poses are in the PR2's base frame (x forward, y left, z up; the floor at -0.051 m).

#include "lmk/demos/detail/demo_task_definitions.h"
#include "lmk/geometry/error.h"

namespace lmk::detail {
namespace {

// A box mesh as a piece of the world: a wall behind the rack, a stand under the panel.
ObjectModel slab(const Eigen::Vector3d& size) {
  ObjectModel o = make_clutter_box(size);
  o.kind = "slab";
  return o;
}

// --- Task 1: hanging tools ---------------------------------------------------------------------

constexpr int kMounts = 3;
constexpr double kRackBottom = kFloorInBase + 0.42;  // the mounts' hooks at about 0.87 m

// The rack on a wall, facing the robot; `dy` and `yaw` move it.
void add_rack(DemoWorld& w, const std::vector<int>& hanging, double dx, double dy, double yaw) {
  const ObjectModel rack = make_tool_rack(kMounts, hanging);
  const Eigen::Isometry3d T = facing_robot(0.68 + dx, dy, kRackBottom, yaw);
  std::vector<std::pair<std::string, std::string>> parts;
  for (const ObjectPart& p : rack.parts) {
    parts.emplace_back(p.name.rfind("griple", 0) == 0 ? "griple" : "griple_mount", p.name);
  }
  w.add("rack", rack, T, parts);
  w.add("wall", slab({2.0, 0.02, 1.6}), T * pose_from_xyz_rpy({0, 0.02, -0.4}, {0, 0, 0}));
}

// Where the hand holds a tool hanging on mount i: the middle of its handle, approaching the wall
// horizontally, fingers closing across the handle. In the rack's frame (front towards -y).
Eigen::Isometry3d tool_handle_on_mount(int i) {
  const double x = -0.5 * (0.25 * kMounts + 0.1) + 0.05 + 0.25 * (i + 0.5);
  // The rack's -y is the robot's +x: the tool's x axis points into the wall, along +y here.
  return pose_from_xyz_rpy({x, -0.0775, 0.5 - 0.07}, {0, 0, 0.5 * M_PI});
}

}  // namespace

DemoTask hanging_tools_task() {
  DemoTask t = new_task(1, "hanging tools", 0.2, {0.65, 0.0, 0.8});
  // Demonstration: tools on the outer mounts, the middle one free.
  add_rack(t.demonstration, {0, 2}, 0, 0, 0);
  t.landmarks = {part_landmark("griple", "rack", "griple_2"),
                 part_landmark("griple_mount", "rack", "mount_1")};
  const Eigen::Isometry3d T_rack = t.demonstration.object("rack")->T_base_object;
  const auto at_handle = [&](int mount, const Eigen::Vector3d& offset) {
    Eigen::Isometry3d T = T_rack * tool_handle_on_mount(mount);
    T.translation() += offset;
    return T;
  };
  const auto open = GripperAction::kOpen, close = GripperAction::kClose;
  // Pick the tool on mount 2: in front of its handle, onto it, lift it off the lip, back away.
  t.programs.push_back({"pick tool",
                        {"griple"},
                        {right_arm_step("griple", at_handle(2, {-0.12, 0, 0}), open),
                         right_arm_step("griple", at_handle(2, {0, 0, 0}), close),
                         right_arm_step("griple", at_handle(2, {0, 0, 0.06}), close),
                         right_arm_step("griple", at_handle(2, {-0.12, 0, 0.06}), close)}});
  // Hang a held tool on the free mount 1: in front of it, over the lip, down onto it, let go.
  t.programs.push_back({"place tool",
                        {"griple_mount"},
                        {right_arm_step("griple_mount", at_handle(1, {-0.12, 0, 0.06}), close),
                         right_arm_step("griple_mount", at_handle(1, {0, 0, 0.06}), close),
                         right_arm_step("griple_mount", at_handle(1, {0, 0, 0}), open),
                         right_arm_step("griple_mount", at_handle(1, {-0.12, 0, 0}), open)}});

  const auto scenario = [](std::string name, std::string program, std::vector<int> hanging,
                           double dx, double dy, double yaw, std::string missing = "") {
    DemoScenario s = new_scenario(std::move(name), std::move(program), std::move(missing));
    add_rack(s.world, hanging, dx, dy, yaw);
    return s;
  };
  t.scenarios = {
      scenario("take the only tool from a rack", "pick tool", {1}, 0.03, -0.06, 0.08),
      scenario("take a tool from a full rack", "pick tool", {0, 1, 2}, -0.02, 0.05, -0.06),
      scenario("take a tool from a rack with none (should not act)", "pick tool", {}, 0.0, 0.04,
               0.05, "griple"),
      scenario("place a tool on an empty rack", "place tool", {}, 0.02, -0.05, -0.08),
      scenario("place a tool on a full rack (should not act)", "place tool", {0, 1, 2}, -0.03, 0.0,
               0.1, "griple_mount"),
  };
  return t;
}

// --- Task 2: chair -----------------------------------------------------------------------------

namespace {

// The chair with its back to the robot: the backrest (at +y of the chair) towards -x.
void add_chair(DemoWorld& w, double lift, double x, double y, double yaw) {
  const ObjectModel chair = make_chair_at_height(lift);
  w.add("chair", chair, pose_from_xyz_rpy({x, y, kFloorInBase}, {0, 0, 0.5 * M_PI + yaw}),
        {{"backrest_top", "backrest_top"}});
}

}  // namespace

DemoTask chair_task() {
  DemoTask t = new_task(2, "chair", 0.25, {0.75, 0.0, 0.8});
  add_chair(t.demonstration, 0.0, 0.92, 0.0, 0.0);
  t.landmarks = {part_landmark("backrest_top", "chair", "backrest_top")};
  // Both hands on the backrest's top roll, 17 cm either side of its middle, reaching over it from
  // behind: each tool horizontal and pointing into the chair, fingers closing from above and below
  // the roll.
  const Box top = t.demonstration.instances("backrest_top").at(0).first;
  const Eigen::Isometry3d T_chair = t.demonstration.object("chair")->T_base_object;
  const auto on_roll = [&](double side, double back) {
    // The roll's centre is the box's centre height (the box spans 10 cm below the top and 3 cm
    // above, and the roll's radius is 3.5 cm). The chair's -y points away from the robot.
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear().col(0) = -Eigen::Vector3d::UnitY();  // approach: into the chair
    T.linear().col(1) = Eigen::Vector3d::UnitZ();   // fingers close vertically
    T.linear().col(2) = T.linear().col(0).cross(T.linear().col(1));
    T.translation() = Eigen::Vector3d(side, 0.2 + back, top.center().z() - kFloorInBase);
    return T_chair * T;
  };
  DemoStep approach, grasp;
  approach.left = DemoArmPose{"backrest_top", on_roll(0.17, 0.1), GripperAction::kOpen};
  approach.right = DemoArmPose{"backrest_top", on_roll(-0.17, 0.1), GripperAction::kOpen};
  grasp.left = DemoArmPose{"backrest_top", on_roll(0.17, 0.0), GripperAction::kClose};
  grasp.right = DemoArmPose{"backrest_top", on_roll(-0.17, 0.0), GripperAction::kClose};
  t.programs.push_back({"grasp backrest", {"backrest_top"}, {approach, grasp}});

  const auto scenario = [](std::string name, double lift, double x, double y, double yaw) {
    DemoScenario s = new_scenario(std::move(name), "grasp backrest");
    add_chair(s.world, lift, x, y, yaw);
    return s;
  };
  t.scenarios = {
      scenario("raised 6 cm, 8 cm to the left", 0.06, 0.92, 0.08, 0.0),
      scenario("lowered 12 cm, 5 cm further", -0.12, 0.97, 0.0, 0.05),
      scenario("raised 10 cm, turned 20 degrees", 0.10, 0.9, -0.03, 0.35),
      scenario("10 cm to the right, turned -15 degrees", 0.0, 0.88, -0.1, -0.26),
      scenario("turned 50 degrees (the paper missed this)", 0.0, 0.85, 0.05, 0.87),
  };
  return t;
}

// --- Task 3: bowls on a shelf -------------------------------------------------------------------

namespace {

constexpr double kShelfX = 0.74;
const double kBoards[2] = {kFloorInBase + 0.45, kFloorInBase + 0.85};

void add_shelf(DemoWorld& w) {
  w.add("shelf", make_shelf(), facing_robot(kShelfX, 0.0, kFloorInBase));
}

// A bowl on shelf `level` (0 bottom, 1 top) at `y`, with a paper cup touching it on one side. On
// the bottom shelf the bowl stands near the front: further in, the top board hides its far rim
// from the head (a person would put it where they can see it too).
void add_bowl_with_cup(DemoWorld& w, const std::string& id, int level, double y, double yaw) {
  const double z = kBoards[level], x = level == 0 ? kShelfX - 0.07 : kShelfX;
  w.add(id, make_bowl(), pose_from_xyz_rpy({x, y, z}, {0, 0, yaw}), {{"bowl_rim", "rim"}});
  w.add(id + "_cup", make_cup(), pose_from_xyz_rpy({x - 0.03, y + 0.118, z}, {0, 0, 0}));
}

}  // namespace

DemoTask bowls_on_shelf_task() {
  // The torso down: the head then sees under the top board, onto the bottom shelf.
  DemoTask t = new_task(3, "bowls on a shelf", 0.0, {0.75, 0.0, 0.6});
  add_shelf(t.demonstration);
  // The demonstrator sets the bowl apart to capture its rim: a cup inside the box would become
  // part of the landmark. The test scenes put cups against the bowls.
  t.demonstration.add("bowl", make_bowl(),
                      pose_from_xyz_rpy({kShelfX, -0.05, kBoards[1]}, {0, 0, 0}),
                      {{"bowl_rim", "rim"}});
  t.demonstration.add("cup", make_cup(), pose_from_xyz_rpy({kShelfX, 0.2, kBoards[1]}, {0, 0, 0}));
  // The rim is round: any turn about its axis is the same rim. Cups stand against the bowls in
  // the test scenes, and bowls nest in stacks, so the user draws the box tight around the rim
  // (5 mm out, the top 3 cm, 2 cm above): its margins claim free space only inside the bowl and
  // above it, not where a cup touches the bowl.
  DemoLandmark rim_landmark =
      part_landmark("bowl_rim", "bowl", "rim", Symmetry{Eigen::Vector3d::UnitZ(), 0});
  rim_landmark.drawn = Box(pose_from_xyz_rpy({0, 0, 0.06}, {0, 0, 0}), {0.17, 0.17, 0.05});
  t.landmarks = {rim_landmark};
  // Grasp the rim's near side reaching in and down at 45 degrees, fingers closing across the
  // bowl's wall; lift it; take it out to a place beside the robot. (Steeper, the forearm rises
  // behind the wrist into the shelf's roof, 33 cm above the top board: a demonstrator guiding the
  // arm keeps it clear.)
  const Eigen::Isometry3d T_bowl = t.demonstration.object("bowl")->T_base_object;
  const Eigen::Vector3d rim = T_bowl * Eigen::Vector3d(-0.075, 0, 0.065 - 0.015);
  const auto tool_at = [](const Eigen::Vector3d& p) {
    return pose_from_xyz_rpy(p, {0.5 * M_PI, M_PI / 4.0, 0.0});
  };
  const Eigen::Vector3d approach = tool_at(rim).linear().col(0);
  t.programs.push_back(
      {"pick bowl",
       {"bowl_rim"},
       {right_arm_step("bowl_rim", tool_at(rim - 0.1 * approach), GripperAction::kOpen),
        right_arm_step("bowl_rim", tool_at(rim), GripperAction::kClose),
        right_arm_step("bowl_rim", tool_at(rim + Eigen::Vector3d(0, 0, 0.05)),
                       GripperAction::kClose),
        right_arm_step(kBaseFrame, tool_at({0.45, -0.45, 0.85}), GripperAction::kClose)}});

  const auto scenario = [](std::string name, bool continues) {
    DemoScenario s = new_scenario(std::move(name), "pick bowl");
    s.continues_previous = continues;
    return s;
  };
  DemoScenario one = scenario("scene 1: bowls on both shelves, first pick", false);
  add_shelf(one.world);
  add_bowl_with_cup(one.world, "top_bowl", 1, 0.1, 0.3);
  add_bowl_with_cup(one.world, "bottom_bowl", 0, -0.12, -0.5);
  DemoScenario two = scenario("scene 2: two stacked bowls, first pick", false);
  add_shelf(two.world);
  add_bowl_with_cup(two.world, "lower_bowl", 1, 0.02, 0.0);
  // The upper bowl nests 1.8 cm higher and hides the lower one's rim until it is picked.
  two.world.add("upper_bowl", make_bowl(),
                pose_from_xyz_rpy({kShelfX, 0.02, kBoards[1] + 0.018}, {0, 0, 1.1}),
                {{"bowl_rim", "rim"}});
  two.world.hide_under("lower_bowl", "upper_bowl");
  DemoScenario three = new_scenario("scene 3: only cups (should not act)", "pick bowl", "bowl_rim");
  add_shelf(three.world);
  for (const auto& [level, y] : {std::pair{1, -0.1}, std::pair{1, 0.12}, std::pair{0, 0.0}}) {
    three.world.add("cup_" + std::to_string(level) + "_" + std::to_string(y), make_cup(),
                    pose_from_xyz_rpy({kShelfX, y, kBoards[level]}, {0, 0, 0}));
  }
  t.scenarios = {one, scenario("scene 1: second pick", true), two,
                 scenario("scene 2: second pick", true), three};
  return t;
}

}  // namespace lmk::detail
