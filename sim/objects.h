// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The procedural object library of the synthetic benchmark (docs/datasets.md, "The synthetic
// benchmark"): the objects of the paper's 17 scenes, built from a few mesh primitives. Shapes only
// need to be recognisable, and to pose the same difficulties as the real ones: a bowl's rim, a
// spray bottle's trigger head, a backrest's corners, a handle proud of a drawer front.
//
// Every object is a mesh in its own frame: z up, resting on z = 0 (walls and panels stand on it),
// the front facing -y. Each lists the landmarks a user would cut from it, as the boxes they would
// draw: around the part, with empty margins where space must stay free, never below a supporting
// surface.

#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/sim/mesh.h"

namespace lmk {

/// A landmark box on an object, in the object frame.
struct ObjectPart {
  std::string name;
  Box box;
};

struct ObjectModel {
  std::string kind;
  TriangleMesh mesh;              ///< object frame
  Box bounds;                     ///< the mesh's bounding box, object frame (axis-aligned)
  std::vector<ObjectPart> parts;  ///< named landmark boxes, object frame
  std::vector<double> surfaces;   ///< heights where other objects can rest (table top, shelves)

  /// The part called `name`; throws lmk::Error naming the known parts when there is none.
  const ObjectPart& part(const std::string& name) const;
};

/// The axis-aligned bounding box of a mesh's vertices (a unit box at the origin for no vertex).
Box mesh_bounds(const TriangleMesh& mesh);

// Tabletop objects. Parts: "bowl" and "rim" (the top 3 cm) for a bowl; "cup"; "bottle";
// "spray_bottle" and "top" (the trigger head); "ball"; "bin".
ObjectModel make_bowl(double radius = 0.08, double height = 0.065);
ObjectModel make_cup(double radius = 0.04, double height = 0.095);
/// A Tide-like detergent bottle: a rounded block with a handle and a cap.
ObjectModel make_detergent_bottle();
/// A spray bottle: a round body, a neck, and a trigger head with its nozzle and trigger.
ObjectModel make_spray_bottle(double body_height = 0.17);
ObjectModel make_ball(double radius = 0.033);
/// A bin open at the top: a square mouth (`round` false) or a circular one. Parts: "bin" and
/// "opening" (the mouth and the top of the walls).
ObjectModel make_bin(bool round);
ObjectModel make_clutter_box(const Eigen::Vector3d& size);
/// A closed carton standing on its base (a tea or cereal box), as make_clutter_box with the part
/// "carton": the box a user would draw around it.
ObjectModel make_carton(const Eigen::Vector3d& size);

// Furniture. Surfaces give the resting heights.
ObjectModel make_table(const Eigen::Vector3d& size = {1.2, 0.8, 0.72});
/// A two-level shelf: a bottom board at 0.45 m and a top board at 0.85 m, sides and a back.
ObjectModel make_shelf();
/// An office chair's backrest on its post, over a seat. Parts: "left_corner" and "right_corner"
/// (the backrest's top corners) and "backrest_top" (its whole top). `lowered` drops the seat and
/// backrest by 12 cm.
ObjectModel make_chair(bool lowered);
/// The chair with its gas lift raised by `lift` metres (negative lowers it).
ObjectModel make_chair_at_height(double lift);

// Unconventional scenes.
/// A wall panel with `mounts` Griple-like mounts in a row; the mounts listed in `hanging` hold a
/// tool (a handle with a Griple adaptor and a head). Parts: "mount_<i>" for every free mount (a
/// Griple hides the mount it hangs on) and "griple_<i>" for every hanging tool's adaptor.
ObjectModel make_tool_rack(int mounts, const std::vector<int>& hanging);
/// An under-desk drawer unit hanging from a desk top, `drawers` high, each front with a bar
/// handle; drawer `open` (counted from the bottom, -1 for none) is pulled out 20 cm. Parts:
/// "handle_<i>".
ObjectModel make_drawer_unit(int drawers, int open);
/// A control panel: a plate with a dial and a row of buttons. Parts: "dial", "button_<i>".
ObjectModel make_control_panel(int buttons = 3);

}  // namespace lmk
