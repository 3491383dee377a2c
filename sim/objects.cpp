// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/objects.h"

#include <algorithm>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

Eigen::Isometry3d at(double x, double y, double z) {
  return pose_from_xyz_rpy({x, y, z}, {0, 0, 0});
}

// Axis-aligned box between two corners.
Box box_between(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = 0.5 * (lo + hi);
  return Box(pose, hi - lo);
}

// The box a user draws around a part: its bounds grown by `below` on the low sides and `above` on
// the high sides, per axis.
Box drawn_around(const Box& part, const Eigen::Vector3d& below, const Eigen::Vector3d& above) {
  const Eigen::Vector3d half = 0.5 * part.size;
  return box_between(part.center() - half - below, part.center() + half + above);
}

// Around a tabletop object: 2 cm of free space on every side and above, none below the table.
Box drawn_on_table(const Box& bounds) {
  return drawn_around(bounds, {0.02, 0.02, 0.0}, Eigen::Vector3d::Constant(0.02));
}

// Appends a box of `size` centred at (x, y, z) of the object frame.
void add_box(TriangleMesh& mesh, const Eigen::Vector3d& size, double x, double y, double z) {
  mesh.append(make_box_mesh(size), at(x, y, z));
}

// A cylinder along the object's -y axis (out of a wall towards the viewer), centred at (x, y, z).
void add_knob(TriangleMesh& mesh, double radius, double length, double x, double y, double z) {
  mesh.append(make_cylinder_mesh(radius, length, 24),
              pose_from_xyz_rpy({x, y, z}, {0.5 * M_PI, 0, 0}));
}

ObjectModel finish(std::string kind, TriangleMesh mesh) {
  ObjectModel model;
  model.kind = std::move(kind);
  model.bounds = mesh_bounds(mesh);
  model.mesh = std::move(mesh);
  return model;
}

}  // namespace

const ObjectPart& ObjectModel::part(const std::string& name) const {
  std::string known;
  for (const ObjectPart& p : parts) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw Error("object '" + kind + "' has no part '" + name + "' (parts: " + known + ")");
}

Box mesh_bounds(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return Box(Eigen::Isometry3d::Identity(), Eigen::Vector3d::Ones());
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& v : mesh.vertices) bounds.extend(v);
  return box_between(bounds.min(), bounds.max());
}

ObjectModel make_bowl(double radius, double height) {
  // A single sheet flaring from a flat bottom to the rim: the inside shows from above.
  ObjectModel bowl = finish(
      "bowl",
      make_lathe_mesh(
          {{0.0, 0.0}, {0.55 * radius, 0.0}, {0.85 * radius, 0.5 * height}, {radius, height}}, 48));
  bowl.parts.push_back({"bowl", drawn_on_table(bowl.bounds)});
  // The rim: the top 3 cm, with free space above and around (a stack shows only this).
  bowl.parts.push_back({"rim", box_between({-radius - 0.02, -radius - 0.02, height - 0.03},
                                           {radius + 0.02, radius + 0.02, height + 0.02})});
  return bowl;
}

ObjectModel make_cup(double radius, double height) {
  TriangleMesh mesh = make_lathe_mesh({{0.0, 0.0}, {radius, 0.0}, {radius, height}}, 40);
  // A C-shaped handle on +x: two arms and a grip.
  add_box(mesh, {0.03, 0.012, 0.012}, radius + 0.012, 0, 0.75 * height);
  add_box(mesh, {0.03, 0.012, 0.012}, radius + 0.012, 0, 0.3 * height);
  add_box(mesh, {0.012, 0.012, 0.45 * height + 0.012}, radius + 0.027, 0, 0.525 * height);
  ObjectModel cup = finish("cup", std::move(mesh));
  cup.parts.push_back({"cup", drawn_on_table(cup.bounds)});
  return cup;
}

ObjectModel make_detergent_bottle() {
  TriangleMesh mesh;
  const Eigen::Vector3d body(0.15, 0.09, 0.21);
  add_box(mesh, body, 0, 0, 0.5 * body.z());
  // The handle: a bar across the back top, on two posts; the cap at the front top.
  add_box(mesh, {0.02, 0.025, 0.05}, -0.05, 0.02, body.z() + 0.025);
  add_box(mesh, {0.02, 0.025, 0.05}, 0.01, 0.02, body.z() + 0.025);
  add_box(mesh, {0.08, 0.025, 0.02}, -0.02, 0.02, body.z() + 0.06);
  mesh.append(make_cylinder_mesh(0.025, 0.035, 32), at(0.045, -0.015, body.z() + 0.0175));
  ObjectModel bottle = finish("detergent_bottle", std::move(mesh));
  bottle.parts.push_back({"bottle", drawn_on_table(bottle.bounds)});
  return bottle;
}

ObjectModel make_spray_bottle(double body_height) {
  const double r = 0.04, neck = 0.015, h = body_height;
  TriangleMesh mesh = make_lathe_mesh(
      {{0.0, 0.0}, {r, 0.0}, {r, h}, {neck, h + 0.025}, {neck, h + 0.045}, {0.0, h + 0.045}}, 40);
  // The trigger head: a block reaching forward (-y), its nozzle, and the trigger below the front.
  const double head_z = h + 0.045 + 0.025;
  add_box(mesh, {0.035, 0.09, 0.05}, 0, -0.02, head_z);
  add_knob(mesh, 0.008, 0.02, 0, -0.075, head_z + 0.01);
  mesh.append(make_box_mesh({0.02, 0.012, 0.05}),
              pose_from_xyz_rpy({0, -0.05, head_z - 0.045}, {0.35, 0, 0}));
  ObjectModel spray = finish("spray_bottle", std::move(mesh));
  spray.parts.push_back({"spray_bottle", drawn_on_table(spray.bounds)});
  // The top: the head and the neck, with free space around and above.
  const Box& b = spray.bounds;
  const Eigen::Vector3d lo = b.center() - 0.5 * b.size, hi = b.center() + 0.5 * b.size;
  spray.parts.push_back({"top", box_between({lo.x() - 0.02, lo.y() - 0.02, h + 0.01},
                                            {hi.x() + 0.02, hi.y() + 0.02, hi.z() + 0.02})});
  return spray;
}

ObjectModel make_ball(double radius) {
  TriangleMesh mesh;
  mesh.append(make_sphere_mesh(radius, 24, 48), at(0, 0, radius));
  ObjectModel ball = finish("ball", std::move(mesh));
  ball.parts.push_back(
      {"ball", drawn_around(ball.bounds, {0.015, 0.015, 0.0}, Eigen::Vector3d::Constant(0.015))});
  return ball;
}

ObjectModel make_bin(bool round) {
  const double h = 0.25, wall = 0.008;
  TriangleMesh mesh;
  if (round) {
    mesh = make_lathe_mesh({{0.0, 0.0}, {0.12, 0.0}, {0.13, h}}, 48);
  } else {
    const double w = 0.24;
    add_box(mesh, {w, w, wall}, 0, 0, 0.5 * wall);
    add_box(mesh, {w, wall, h}, 0, -0.5 * (w - wall), 0.5 * h);
    add_box(mesh, {w, wall, h}, 0, 0.5 * (w - wall), 0.5 * h);
    add_box(mesh, {wall, w, h}, -0.5 * (w - wall), 0, 0.5 * h);
    add_box(mesh, {wall, w, h}, 0.5 * (w - wall), 0, 0.5 * h);
  }
  ObjectModel bin = finish(round ? "round_bin" : "square_bin", std::move(mesh));
  bin.parts.push_back({"bin", drawn_on_table(bin.bounds)});
  // The opening: the top 6 cm of the walls, with 2 cm of free space around them and 4 cm above.
  // Inside, the space down to the box's bottom is seen empty, so the mouth's shape tells the bins
  // apart while their bodies are alike.
  const Eigen::Vector3d half = 0.5 * bin.bounds.size, centre = bin.bounds.center();
  const Box top = box_between({centre.x() - half.x(), centre.y() - half.y(), h - 0.06},
                              {centre.x() + half.x(), centre.y() + half.y(), h});
  bin.parts.push_back({"opening", drawn_around(top, {0.02, 0.02, 0.0}, {0.02, 0.02, 0.04})});
  return bin;
}

ObjectModel make_clutter_box(const Eigen::Vector3d& size) {
  TriangleMesh mesh;
  add_box(mesh, size, 0, 0, 0.5 * size.z());
  return finish("box", std::move(mesh));
}

ObjectModel make_carton(const Eigen::Vector3d& size) {
  ObjectModel carton = make_clutter_box(size);
  carton.kind = "carton";
  carton.parts.push_back({"carton", drawn_on_table(carton.bounds)});
  return carton;
}

ObjectModel make_table(const Eigen::Vector3d& size) {
  const double top = 0.04, leg = 0.05;
  TriangleMesh mesh;
  add_box(mesh, {size.x(), size.y(), top}, 0, 0, size.z() - 0.5 * top);
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      add_box(mesh, {leg, leg, size.z() - top}, sx * (0.5 * size.x() - leg),
              sy * (0.5 * size.y() - leg), 0.5 * (size.z() - top));
    }
  }
  ObjectModel table = finish("table", std::move(mesh));
  table.surfaces = {size.z()};
  return table;
}

ObjectModel make_shelf() {
  const double width = 0.8, depth = 0.35, height = 1.2, board = 0.02;
  TriangleMesh mesh;
  add_box(mesh, {board, depth, height}, -0.5 * (width - board), 0, 0.5 * height);
  add_box(mesh, {board, depth, height}, 0.5 * (width - board), 0, 0.5 * height);
  add_box(mesh, {width, board, height}, 0, 0.5 * (depth - board), 0.5 * height);
  std::vector<double> surfaces;
  for (const double z : {0.45, 0.85, height}) {
    add_box(mesh, {width, depth, board}, 0, 0, z - 0.5 * board);
    if (z < height) surfaces.push_back(z);
  }
  ObjectModel shelf = finish("shelf", std::move(mesh));
  shelf.surfaces = surfaces;
  return shelf;
}

ObjectModel make_chair(bool lowered) { return make_chair_at_height(lowered ? -0.12 : 0.0); }

ObjectModel make_chair_at_height(double lift) {
  const double drop = -lift;
  const double seat_z = 0.45 - drop, back_bottom = 0.62 - drop, back_height = 0.42;
  // A padded backrest: a slab whose top is a rounded roll. The roll also gives the corner relief,
  // which a flat slab would not (its corner would be a plane with a grazing top).
  const double roll = 0.035;
  const Eigen::Vector3d back(0.44, 2.0 * roll, back_height - roll);
  const double back_y = 0.2;
  TriangleMesh mesh;
  // A five-spoke base, the gas post, the seat, the backrest's post and the backrest.
  for (int k = 0; k < 5; ++k) {
    mesh.append(
        make_box_mesh({0.3, 0.04, 0.03}),
        pose_from_xyz_rpy({0.15 * std::cos(k * 0.4 * M_PI), 0.15 * std::sin(k * 0.4 * M_PI), 0.015},
                          {0, 0, k * 0.4 * M_PI}));
  }
  mesh.append(make_cylinder_mesh(0.025, seat_z - 0.03, 24), at(0, 0, 0.5 * (seat_z + 0.03)));
  add_box(mesh, {0.46, 0.46, 0.06}, 0, 0, seat_z + 0.03);
  add_box(mesh, {0.05, 0.03, back_bottom - seat_z}, 0, back_y + 0.03, 0.5 * (seat_z + back_bottom));
  add_box(mesh, back, 0, back_y, back_bottom + 0.5 * back.z());
  mesh.append(make_cylinder_mesh(roll, back.x(), 24),
              pose_from_xyz_rpy({0, back_y, back_bottom + back.z()}, {0, 0.5 * M_PI, 0}));
  ObjectModel chair = finish(drop > 0.0 ? "lowered_chair" : "chair", std::move(mesh));
  // A corner: 9 cm of backrest below and inside the corner, 3 cm of free space above and outside.
  const double top = back_bottom + back_height;
  for (const double side : {-1.0, 1.0}) {
    const double edge = side * 0.5 * back.x();
    const double inner = edge - side * 0.09, outer = edge + side * 0.03;
    chair.parts.push_back({side < 0 ? "left_corner" : "right_corner",
                           box_between({std::min(inner, outer), back_y - 0.06, top - 0.09},
                                       {std::max(inner, outer), back_y + 0.06, top + 0.03})});
  }
  // The whole top of the backrest, corner to corner: its top 10 cm and 3 cm of free space around.
  chair.parts.push_back(
      {"backrest_top", box_between({-0.5 * back.x() - 0.03, back_y - 0.06, top - 0.1},
                                   {0.5 * back.x() + 0.03, back_y + 0.06, top + 0.03})});
  return chair;
}

ObjectModel make_tool_rack(int mounts, const std::vector<int>& hanging) {
  if (mounts < 1) throw Error("tool rack: needs at least one mount");
  const double width = 0.25 * mounts + 0.1, height = 0.7, mount_z = 0.5;
  TriangleMesh mesh;
  add_box(mesh, {width, 0.02, height}, 0, 0, 0.5 * height);  // the wall panel; front at y = -0.01
  std::vector<ObjectPart> parts;
  for (int i = 0; i < mounts; ++i) {
    const double x = -0.5 * width + 0.05 + 0.25 * (i + 0.5);
    // A mount: a wall plate with a hook block at its top, whose raised lip a Griple hooks on.
    // Plate below, hook above: no turn in the wall's plane maps it onto itself.
    add_box(mesh, {0.08, 0.012, 0.1}, x, -0.016, mount_z - 0.01);
    add_box(mesh, {0.05, 0.04, 0.03}, x, -0.042, mount_z + 0.025);
    add_box(mesh, {0.05, 0.01, 0.03}, x, -0.057, mount_z + 0.05);
    // A mount with a tool on it is hidden behind the Griple: only free mounts are instances.
    if (std::find(hanging.begin(), hanging.end(), i) != hanging.end()) continue;
    parts.push_back(
        {"mount_" + std::to_string(i),
         box_between({x - 0.05, -0.1, mount_z - 0.05}, {x + 0.05, -0.005, mount_z + 0.07})});
  }
  for (const int i : hanging) {
    if (i < 0 || i >= mounts) throw Error("tool rack: no mount " + std::to_string(i));
    const double x = -0.5 * width + 0.05 + 0.25 * (i + 0.5);
    // The Griple: a block hooked over the lip, the tool's handle below it and its head.
    add_box(mesh, {0.045, 0.035, 0.06}, x, -0.0775, mount_z + 0.02);
    mesh.append(make_cylinder_mesh(0.015, 0.16, 24), at(x, -0.0775, mount_z - 0.09));
    add_box(mesh, {0.07, 0.02, 0.05}, x, -0.0775, mount_z - 0.195);
    parts.push_back(
        {"griple_" + std::to_string(i),
         box_between({x - 0.05, -0.13, mount_z - 0.03}, {x + 0.05, -0.005, mount_z + 0.08})});
  }
  ObjectModel rack = finish("tool_rack", std::move(mesh));
  rack.parts = std::move(parts);
  return rack;
}

ObjectModel make_drawer_unit(int drawers, int open) {
  if (drawers < 1) throw Error("drawer unit: needs at least one drawer");
  if (open >= drawers) throw Error("drawer unit: no drawer " + std::to_string(open));
  const double desk_z = 0.73, width = 0.4, depth = 0.5, height = 0.45, pull = 0.2;
  const double front_y = -0.5 * depth, cabinet_bottom = desk_z - 0.03 - height;
  TriangleMesh mesh;
  add_box(mesh, {1.2, 0.6, 0.03}, 0.3, 0.05, desk_z - 0.015);  // the desk top it hangs from
  add_box(mesh, {0.03, 0.6, desk_z - 0.03}, 0.885, 0.05, 0.5 * (desk_z - 0.03));  // a desk side
  // The cabinet, open at the front: sides, back and bottom.
  add_box(mesh, {0.015, depth, height}, -0.5 * width, 0, cabinet_bottom + 0.5 * height);
  add_box(mesh, {0.015, depth, height}, 0.5 * width, 0, cabinet_bottom + 0.5 * height);
  add_box(mesh, {width, 0.015, height}, 0, 0.5 * depth, cabinet_bottom + 0.5 * height);
  add_box(mesh, {width, depth, 0.015}, 0, 0, cabinet_bottom + 0.0075);
  std::vector<ObjectPart> parts;
  const double drawer_h = height / drawers;
  for (int i = 0; i < drawers; ++i) {
    const double y = front_y - 0.01 - (i == open ? pull : 0.0);
    const double z = cabinet_bottom + (i + 0.5) * drawer_h;
    add_box(mesh, {width - 0.01, 0.02, drawer_h - 0.01}, 0, y, z);
    if (i == open) {  // the drawer's box, pulled out with its front: open at the top
      const double inner_y = y + 0.01 + 0.5 * pull;
      add_box(mesh, {0.01, pull, drawer_h - 0.04}, -0.5 * width + 0.02, inner_y, z - 0.01);
      add_box(mesh, {0.01, pull, drawer_h - 0.04}, 0.5 * width - 0.02, inner_y, z - 0.01);
      add_box(mesh, {width - 0.04, pull, 0.01}, 0, inner_y, z - 0.5 * drawer_h + 0.02);
    }
    // A bar handle on two standoffs, 3.5 cm proud of the front: chunky enough for a Kinect at a
    // metre and a half (5 mm noise) to see the bar's ends and the standoffs, which fix it along
    // its length.
    const double hy = y - 0.01;
    add_box(mesh, {0.02, 0.03, 0.02}, -0.045, hy - 0.015, z);
    add_box(mesh, {0.02, 0.03, 0.02}, 0.045, hy - 0.015, z);
    mesh.append(make_cylinder_mesh(0.011, 0.13, 16),
                pose_from_xyz_rpy({0, hy - 0.035, z}, {0, 0.5 * M_PI, 0}));
    parts.push_back({"handle_" + std::to_string(i),
                     box_between({-0.1, hy - 0.07, z - 0.035}, {0.1, hy + 0.005, z + 0.035})});
  }
  ObjectModel unit = finish(open >= 0 ? "drawer_unit_open" : "drawer_unit", std::move(mesh));
  unit.parts = std::move(parts);
  return unit;
}

ObjectModel make_control_panel(int buttons) {
  const double width = 0.34, height = 0.22;
  TriangleMesh mesh;
  add_box(mesh, {width, 0.02, height}, 0, 0, 0.5 * height);
  // The dial: a knob with a grip bar from its centre to its rim, which is also its pointer (as on a
  // washing machine: the bar is what a hand turns, and no turn of the knob looks the same); the
  // buttons in a row to its right.
  add_knob(mesh, 0.03, 0.025, -0.09, -0.0225, 0.11);
  add_box(mesh, {0.014, 0.015, 0.034}, -0.09, -0.0425, 0.122);
  ObjectModel panel;
  std::vector<ObjectPart> parts;
  parts.push_back({"dial", box_between({-0.135, -0.07, 0.065}, {-0.045, -0.005, 0.155})});
  for (int i = 0; i < buttons; ++i) {
    const double x = 0.0 + 0.05 * i;
    add_knob(mesh, 0.012, 0.014, x, -0.017, 0.11);
    parts.push_back({"button_" + std::to_string(i),
                     box_between({x - 0.025, -0.05, 0.085}, {x + 0.025, -0.005, 0.135})});
  }
  panel = finish("control_panel", std::move(mesh));
  panel.parts = std::move(parts);
  return panel;
}

}  // namespace lmk
