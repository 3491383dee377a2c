// SPDX-License-Identifier: BSD-3-Clause
// Tasks 4-6 of the paper's PbD demonstrations: trash versus recycling bins, an empty spot on a
// crowded table, a control panel. Poses are in the PR2's base frame (x forward, y left, z up; the
// floor at -0.051 m).

#include "lmk/demos/detail/demo_task_definitions.h"
#include "lmk/geometry/error.h"

namespace lmk::detail {

const DemoLandmark& DemoTask::landmark(const std::string& name) const {
  for (const DemoLandmark& l : landmarks) {
    if (l.name == name) return l;
  }
  throw Error("demo task " + std::to_string(number) + ": no landmark '" + name + "'");
}

std::vector<DemoTask> demo_task_definitions() {
  return {hanging_tools_task(), chair_task(),         bowls_on_shelf_task(), bins_task(),
          crowded_table_task(), control_panel_task(), obstacles_task()};
}

// --- Task 4: trash and recycling bins ----------------------------------------------------------

void add_bins(DemoWorld& w, std::optional<Eigen::Vector3d> trash, Eigen::Vector3d recycling) {
  // Each (x, y, yaw).
  if (trash) {
    w.add("trash", make_bin(false),
          pose_from_xyz_rpy({trash->x(), trash->y(), kFloorInBase}, {0, 0, trash->z()}),
          {{"trash_opening", "opening"}});
  }
  w.add("recycling", make_bin(true),
        pose_from_xyz_rpy({recycling.x(), recycling.y(), kFloorInBase}, {0, 0, recycling.z()}),
        {{"recycling_opening", "opening"}});
}

void add_bin_programs(DemoTask& t) {
  // A square mouth looks the same a quarter turn round; a round one, any turn round.
  t.landmarks = {
      part_landmark("trash_opening", "trash", "opening", Symmetry{Eigen::Vector3d::UnitZ(), 4}),
      part_landmark("recycling_opening", "recycling", "opening",
                    Symmetry{Eigen::Vector3d::UnitZ(), 0})};
  // Hold an item 20 cm over the mouth's centre, let go, move up.
  for (const auto& [bin, landmark, program] :
       {std::tuple{"trash", "trash_opening", "drop in trash"},
        std::tuple{"recycling", "recycling_opening", "drop in recycling"}}) {
    const Eigen::Vector3d mouth =
        t.demonstration.instances(landmark).at(0).first.center() + Eigen::Vector3d(0, 0, 0.02);
    DemoStep over, drop, up;
    over.right = DemoArmPose{landmark, pointing_down(mouth + Eigen::Vector3d(0, 0, 0.2)),
                             GripperAction::kClose};
    drop.right = DemoArmPose{landmark, over.right->T_base_ee, GripperAction::kOpen};
    up.right = DemoArmPose{landmark, pointing_down(mouth + Eigen::Vector3d(0, 0, 0.3)),
                           GripperAction::kOpen};
    t.programs.push_back({program, {landmark}, {over, drop, up}});
  }
}

DemoTask bins_task() {
  DemoTask t = new_task(4, "trash vs recycling", 0.05, {0.6, 0.0, 0.1});
  add_bins(t.demonstration, Eigen::Vector3d(kBinX, 0.2, 0.0), {kBinX, -0.2, 0.0});
  add_bin_programs(t);
  const auto scenario = [](std::string name, std::string program,
                           std::optional<Eigen::Vector3d> trash, Eigen::Vector3d recycling,
                           std::string missing = "") {
    DemoScenario s = new_scenario(std::move(name), std::move(program), std::move(missing));
    add_bins(s.world, trash, recycling);
    return s;
  };
  const double turn = 0.25 * M_PI;
  t.scenarios = {
      scenario("drop in trash, bins moved slightly", "drop in trash",
               Eigen::Vector3d(kBinX + 0.04, 0.24, 0.1), {kBinX - 0.03, -0.17, -0.2}),
      scenario("drop in trash, bins swapped", "drop in trash", Eigen::Vector3d(kBinX, -0.2, 0.0),
               {kBinX, 0.2, 0.0}),
      scenario("drop in recycling, bins turned 45 degrees", "drop in recycling",
               Eigen::Vector3d(kBinX, 0.2, turn), {kBinX, -0.2, turn}),
      scenario("drop in trash, only recycling there (should not act)", "drop in trash",
               std::nullopt, {kBinX + 0.02, 0.05, 0.3}, "trash_opening"),
      scenario("drop in recycling, only recycling there", "drop in recycling", std::nullopt,
               {kBinX + 0.02, 0.05, 0.3}),
  };
  // Issue #48: a person moves the trash bin as the arm arrives over it, before it lets go.
  DemoScenario pushed =
      scenario("drop in trash, trash pushed 11 cm as the arm arrives", "drop in trash",
               Eigen::Vector3d(kBinX, 0.2, 0.0), {kBinX, -0.2, 0.0});
  pushed.move =
      DemoMove{"trash", pose_from_xyz_rpy({kBinX - 0.02, 0.09, kFloorInBase}, {0, 0, 0.2}), 1};
  DemoScenario taken =
      scenario("drop in trash, trash carried off as the arm arrives (should stop)", "drop in trash",
               Eigen::Vector3d(kBinX, 0.2, 0.0), {kBinX, -0.2, 0.0}, "trash_opening");
  taken.move = DemoMove{"trash", std::nullopt, 1};
  t.scenarios.push_back(pushed);
  t.scenarios.push_back(taken);
  return t;
}

// --- Task 5: an empty spot on a crowded table -------------------------------------------------

namespace {

constexpr double kTableHeight = 0.72;
constexpr double kTableTop = kFloorInBase + kTableHeight;
constexpr double kTableX = 0.85;               // centre; its near edge 0.4 m in front of the robot
const Eigen::Vector3d kPatch(0.2, 0.2, 0.13);  // the box a user draws: 20 cm square, 12 cm free

// The table, 1.2 m wide across the robot's view, with its top as a free surface for the patch.
void add_table(DemoWorld& w) {
  const Eigen::Isometry3d T = pose_from_xyz_rpy({kTableX, 0, kFloorInBase}, {0, 0, 0.5 * M_PI});
  w.add("table", make_table({1.2, 0.8, kTableHeight}), T);
  Box top(pose_from_xyz_rpy({kTableX, 0, kTableTop}, {0, 0, 0}), {0.8, 1.2, 0.0});
  // The patch box's centre stands half its height above its bottom, 1 cm under the top.
  w.add_free_surface({"empty_patch", top, 0.5 * kPatch.z() - 0.01});
}

// Clutter on the table: each (x, y, kind) with kind 0 a box, 1 a bowl, 2 a cup, 3 a spray bottle.
void add_clutter(DemoWorld& w, const std::vector<Eigen::Vector3d>& items) {
  int n = 0;
  for (const Eigen::Vector3d& item : items) {
    const Eigen::Isometry3d T = pose_from_xyz_rpy({item.x(), item.y(), kTableTop}, {0, 0, 0.4 * n});
    const std::string id = "item_" + std::to_string(n++);
    switch (static_cast<int>(item.z())) {
      case 0:
        w.add(id, make_clutter_box({0.12, 0.1, 0.15}), T);
        break;
      case 1:
        w.add(id, make_bowl(), T);
        break;
      case 2:
        w.add(id, make_cup(), T);
        break;
      default:
        w.add(id, make_spray_bottle(), T);
    }
  }
}

// A flat box larger than the patch: its top is as empty and as flat as the patch, 6-10 cm higher.
void add_flat_box(DemoWorld& w, double x, double y, double height) {
  w.add("flat_box", make_clutter_box({0.34, 0.3, height}),
        pose_from_xyz_rpy({x, y, kTableTop}, {0, 0, 0.1}));
}

}  // namespace

DemoTask crowded_table_task() {
  DemoTask t = new_task(5, "crowded table", 0.2, {0.8, 0.0, kTableTop});
  add_table(t.demonstration);
  add_clutter(t.demonstration, {{0.6, 0.3, 0}, {0.75, -0.35, 1}, {0.95, 0.05, 2}});
  const Eigen::Vector3d patch_centre(0.62, -0.05, kTableTop - 0.01 + 0.5 * kPatch.z());
  DemoLandmark patch;
  patch.name = "empty_patch";
  patch.box = Box(pose_from_xyz_rpy(patch_centre, {0, 0, 0}), kPatch);
  patch.flat = true;
  // Where on a free surface a patch lies is open, and so is its heading: a turn about the vertical
  // leaves it the same patch.
  patch.symmetry = Symmetry{Eigen::Vector3d::UnitZ(), 0};
  // Only patches at the demonstrated height: the paper's remedy for the flat box it took for the
  // table ("compare the heights of the multiple empty patches").
  patch.select = InstancePolicy::kDemonstratedHeight;
  t.landmarks = {patch};
  DemoStep point, back;
  point.right = DemoArmPose{"empty_patch",
                            pointing_down(patch_centre + Eigen::Vector3d(0, 0, 0.12), 0.5 * M_PI),
                            GripperAction::kClose};
  back.right =
      DemoArmPose{kBaseFrame, pointing_down({0.4, -0.45, 0.95}, 0.5 * M_PI), GripperAction::kClose};
  t.programs.push_back({"point to empty spot", {"empty_patch"}, {point, back}});

  const auto scenario = [](std::string name, std::vector<Eigen::Vector3d> items) {
    DemoScenario s = new_scenario(std::move(name), "point to empty spot");
    add_table(s.world);
    add_clutter(s.world, items);
    return s;
  };
  DemoScenario box_left =
      scenario("free spot on the right, a flat box on the left",
               {{0.6, 0.05, 0}, {0.9, -0.1, 2}, {0.62, -0.45, 3}, {0.95, 0.25, 1}});
  add_flat_box(box_left.world, 0.7, 0.35, 0.06);
  // The free spot within the arm's reach is on the left; a flat box, larger than the patch, stands
  // in front on the right.
  DemoScenario box_right =
      scenario("free spot on the left, a flat box on the right",
               {{0.62, -0.1, 0}, {0.9, 0.25, 2}, {1.0, -0.1, 3}, {0.85, -0.4, 1}});
  add_flat_box(box_right.world, 0.62, -0.42, 0.1);
  t.scenarios = {
      scenario("free spot in front, on the left",
               {{0.6, -0.2, 0}, {0.85, 0.1, 1}, {0.95, -0.3, 3}}),
      scenario("free spot at the back, in the middle",
               {{0.58, 0.0, 1}, {0.6, 0.3, 2}, {0.7, -0.3, 0}, {1.05, 0.35, 3}}),
      scenario("free spot on the right, cluttered left",
               {{0.6, 0.2, 0}, {0.8, 0.35, 1}, {0.95, 0.1, 2}, {0.9, -0.1, 3}}),
      box_left,
      box_right,
  };
  return t;
}

// --- Task 6: control panel ---------------------------------------------------------------------

namespace {

// The panel on a stand, facing the robot, its top leaning back by `incline`; moved by (dx, dy, dz)
// and turned by `yaw`.
void add_panel(DemoWorld& w, double incline, double dx, double dy, double dz, double yaw) {
  const Eigen::Isometry3d T =
      facing_robot(0.62 + dx, dy, 0.78 + dz, yaw) * pose_from_xyz_rpy({0, 0, 0}, {-incline, 0, 0});
  w.add("panel", make_control_panel(3), T, {{"dial", "dial"}});
  ObjectModel stand = make_clutter_box({0.3, 0.2, 0.78 + dz - kFloorInBase});
  w.add("stand", stand,
        facing_robot(0.62 + dx, dy, kFloorInBase, yaw) * pose_from_xyz_rpy({0, 0.1, 0}, {0, 0, 0}));
}

// A button's press point on the panel (its face, 4 mm in), with the tool pointing into the panel.
Eigen::Isometry3d on_button(const Eigen::Isometry3d& T_panel, int button, double out) {
  return T_panel * pose_from_xyz_rpy({0.05 * button, -0.02 - out, 0.11}, {0, 0, 0.5 * M_PI});
}

}  // namespace

DemoTask control_panel_task() {
  DemoTask t = new_task(6, "control panel", 0.2, {0.6, 0.0, 0.85});
  add_panel(t.demonstration, 0.0, 0, 0, 0, 0);
  // The user draws the box around the dial and the panel's corner beside it, 3 cm past its edges:
  // a round knob turns freely about its axis but for its small grip bar, and the corner pins that
  // turn down, where the buttons' positions depend on it.
  DemoLandmark dial = part_landmark("dial", "panel", "dial");
  dial.drawn = Box(pose_from_xyz_rpy({-0.1225, -0.0275, 0.1575}, {0, 0, 0}), {0.155, 0.085, 0.185});
  t.landmarks = {dial};
  // Press buttons 2, 0 and 1: for each, 6 cm in front of it, onto it, and back.
  const Eigen::Isometry3d T_panel = t.demonstration.object("panel")->T_base_object;
  DemoProgram press{"press buttons 2, 0, 1", {"dial"}, {}};
  for (const int button : {2, 0, 1}) {
    for (const double out : {0.06, 0.0, 0.06}) {
      DemoStep s;
      s.right = DemoArmPose{"dial", on_button(T_panel, button, out), GripperAction::kClose};
      press.steps.push_back(s);
    }
  }
  t.programs.push_back(press);
  const auto scenario = [](std::string name, double incline, double dx, double dy, double dz,
                           double yaw) {
    DemoScenario s = new_scenario(std::move(name), "press buttons 2, 0, 1");
    add_panel(s.world, incline, dx, dy, dz, yaw);
    return s;
  };
  const double degree = M_PI / 180.0;
  t.scenarios = {
      scenario("upright, 6 cm to the right", 0.0, 0.0, -0.06, 0.0, 0.0),
      scenario("upright, higher and to the left, turned 10 degrees", 0.0, 0.03, 0.08, 0.08,
               10 * degree),
      scenario("inclined 25 degrees", 25 * degree, 0.0, 0.0, -0.04, 0.0),
      scenario("inclined 40 degrees, turned -15 degrees", 40 * degree, -0.02, -0.04, -0.06,
               -15 * degree),
      scenario("inclined 50 degrees", 50 * degree, 0.02, 0.03, -0.08, 0.0),
  };
  return t;
}

}  // namespace lmk::detail
