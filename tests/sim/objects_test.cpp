// SPDX-License-Identifier: BSD-3-Clause
// The procedural object library: sound meshes, landmark parts that hold visible geometry, and the
// variants (open drawer, lowered chair, full or empty rack) that the scene types rely on.

#include "lmk/sim/objects.h"

#include <gtest/gtest.h>

#include <functional>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/pose.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk {
namespace {

std::vector<ObjectModel> every_object() {
  return {make_bowl(),
          make_cup(),
          make_detergent_bottle(),
          make_spray_bottle(),
          make_ball(),
          make_bin(false),
          make_bin(true),
          make_clutter_box({0.1, 0.2, 0.15}),
          make_table(),
          make_shelf(),
          make_chair(false),
          make_chair(true),
          make_tool_rack(3, {0, 2}),
          make_drawer_unit(3, -1),
          make_drawer_unit(3, 0),
          make_control_panel()};
}

// The object seen by the simulated Kinect from the front (-y) and above, 1.5 m from its bounds'
// centre: a robot's view, with the whole object in the frame.
PointCloud render_from_front(const ObjectModel& object) {
  const Eigen::Vector3d target = object.bounds.center();
  const Eigen::Vector3d eye = target + Eigen::Vector3d(0.15, -1.4, 0.6);
  DepthSensorSettings settings;
  settings.noise = false;
  return render_depth(object.mesh, camera_look_at(eye, target, Eigen::Vector3d::UnitZ()), settings);
}

TEST(Objects, MeshesAreSoundAndTheirBoundsHoldThem) {
  for (const ObjectModel& object : every_object()) {
    SCOPED_TRACE(object.kind);
    ASSERT_FALSE(object.mesh.triangles.empty());
    const int n = static_cast<int>(object.mesh.vertices.size());
    for (const auto& t : object.mesh.triangles) {
      EXPECT_TRUE((t.array() >= 0).all() && (t.array() < n).all());
    }
    const Box grown(object.bounds.pose, object.bounds.size.array() + 1e-9);
    for (const auto& v : object.mesh.vertices) EXPECT_TRUE(grown.contains(v));
    // Resting on z = 0: nothing below, something on it.
    const double bottom = object.bounds.center().z() - 0.5 * object.bounds.size.z();
    EXPECT_NEAR(bottom, 0.0, 1e-9);
    for (const ObjectPart& part : object.parts) EXPECT_TRUE(part.box.is_valid()) << part.name;
  }
}

TEST(Objects, EveryLandmarkPartHoldsVisibleGeometryAndFreeSpace) {
  for (const ObjectModel& object : every_object()) {
    SCOPED_TRACE(object.kind);
    const PointCloud cloud = render_from_front(object);
    for (const ObjectPart& part : object.parts) {
      // Enough points to capture the part from a robot's viewpoint...
      EXPECT_GE(indices_in_box(cloud, part.box).size(), 100u) << part.name;
      // ... and free space in front of it, towards the robot: the empty-space constraint needs
      // observed-empty voxels, so no geometry within 1 cm of the box's front face.
      const double front = part.box.center().y() - 0.5 * part.box.size.y();
      for (const auto& p : cloud.points) {
        if (is_finite(p) && part.box.contains(p)) {
          EXPECT_GT(p.y(), front + 0.01) << part.name;
        }
      }
    }
  }
}

TEST(Objects, OpenShapesShowTheirInsides) {
  // Looking straight down into a bowl, a cup and a bin, the centre ray reaches the bottom.
  for (const ObjectModel& object : {make_bowl(), make_cup(), make_bin(false), make_bin(true)}) {
    SCOPED_TRACE(object.kind);
    const Eigen::Vector3d eye(0, 0, 1.0);
    DepthSensorSettings settings;
    settings.noise = false;
    const PointCloud cloud = render_depth(
        object.mesh, camera_look_at(eye, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()),
        settings);
    const Eigen::Vector3f centre = cloud.points[240 * 640 + 320];
    ASSERT_TRUE(is_finite(centre));
    EXPECT_LT(centre.z(), 0.01);
  }
}

TEST(Objects, VariantsMoveTheirParts) {
  const ObjectModel closed = make_drawer_unit(3, -1), open = make_drawer_unit(3, 0);
  EXPECT_NEAR(closed.part("handle_0").box.center().y() - open.part("handle_0").box.center().y(),
              0.2, 1e-9);
  EXPECT_EQ(closed.part("handle_1").box.center(), open.part("handle_1").box.center());

  const ObjectModel chair = make_chair(false), lowered = make_chair(true);
  EXPECT_NEAR(
      chair.part("left_corner").box.center().z() - lowered.part("left_corner").box.center().z(),
      0.12, 1e-9);

  const ObjectModel rack = make_tool_rack(3, {1});
  EXPECT_NO_THROW(rack.part("mount_0"));
  EXPECT_NO_THROW(rack.part("griple_1"));
  EXPECT_THROW(rack.part("griple_0"), Error);
  EXPECT_THROW(rack.part("mount_1"), Error);  // hidden behind its Griple
  EXPECT_THROW(make_tool_rack(2, {2}), Error);
  EXPECT_THROW(make_drawer_unit(2, 2), Error);
  try {
    make_bowl().part("handle");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("parts: bowl, rim"), std::string::npos) << e.what();
  }

  const ObjectModel shelf = make_shelf();
  ASSERT_EQ(shelf.surfaces.size(), 2u);
  EXPECT_LT(shelf.surfaces[0], shelf.surfaces[1]);
}

}  // namespace
}  // namespace lmk
