// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Triangle meshes for synthetic scenes: primitives centred at their origin, composed by rigid
// transforms. Shapes only need to be recognisable, so the primitives are simple.

#include <Eigen/Geometry>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// The colour of a surface nobody painted: a mid grey, as tables, walls and floors.
inline constexpr Color kUnpainted{150, 150, 150};

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  ///< counter-clockwise seen from outside
  /// Empty (no colour: the sensor renders depth only), or each triangle's surface colour.
  std::vector<Color> colours;

  /// Appends `other` transformed by T_this_other. When only one of the two is painted, the other's
  /// triangles take kUnpainted.
  void append(const TriangleMesh& other,
              const Eigen::Isometry3d& T_this_other = Eigen::Isometry3d::Identity());
};

/// `mesh` with every triangle painted `colour`.
TriangleMesh painted(TriangleMesh mesh, const Color& colour);

/// Axis-aligned box of full side lengths `size`, centred at the origin.
TriangleMesh make_box_mesh(const Eigen::Vector3d& size);
/// Closed cylinder along z, centred at the origin.
TriangleMesh make_cylinder_mesh(double radius, double height, int segments = 32);
/// Surface of revolution about z of the polyline `profile`, each point (radius, z). A point of
/// radius 0 lies on the axis, so a profile from the axis back to the axis is closed, and one that
/// ends off the axis is open there (a cup's mouth, a bowl's rim). Surfaces are single sheets: the
/// simulated sensor sees both sides. Wind the profile from bottom to top along the outside for
/// outward-facing triangles.
TriangleMesh make_lathe_mesh(const std::vector<Eigen::Vector2d>& profile, int segments = 32);
/// UV sphere centred at the origin.
TriangleMesh make_sphere_mesh(double radius, int rings = 16, int segments = 32);

/// The distance of each point to the nearest point of the mesh's surface (CGAL AABB tree), in
/// parallel. For ground-truth checks: whether what a pose says is there lies on the world.
std::vector<double> distances_to_mesh(const TriangleMesh& mesh,
                                      const std::vector<Eigen::Vector3d>& points);

}  // namespace lmk
