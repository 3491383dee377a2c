// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Solid primitives for collision checking (issue #60): a box, a cylinder or a sphere in its own
// frame, with the signed distance from a point to its surface (negative inside), the radius of a
// sphere about its origin that holds it, and points spread over its surface. A robot's links are
// built of them (a URDF's <collision> shapes, its meshes covered by spheres), and a motion is
// checked by asking each solid how far the points of the scene are from it.

#include <Eigen/Core>
#include <vector>

namespace lmk {

class Solid {
 public:
  enum class Kind { box, cylinder, sphere };

  /// A box centred on its origin with full extents `size` (each > 0).
  static Solid box(const Eigen::Vector3d& size);
  /// A cylinder about its z axis, centred on its origin.
  static Solid cylinder(double radius, double length);
  static Solid sphere(double radius);

  Kind kind() const { return kind_; }
  /// Box: full extents; cylinder: (radius, radius, length); sphere: (radius, radius, radius).
  const Eigen::Vector3d& size() const { return size_; }

  /// Distance from `p` (solid frame) to the surface: positive outside, negative inside.
  double signed_distance(const Eigen::Vector3d& p) const;
  /// The radius of the smallest sphere about the origin that holds the solid.
  double bounding_radius() const;
  /// Points on the surface, no two neighbours farther apart than about `spacing` (> 0): for
  /// checking one solid against another, and a mesh against a solid.
  std::vector<Eigen::Vector3d> surface_points(double spacing) const;

 private:
  Solid(Kind kind, const Eigen::Vector3d& size) : kind_(kind), size_(size) {}
  Kind kind_;
  Eigen::Vector3d size_;
};

/// Spheres that cover `points` (a mesh's vertices and surface samples): the points are gathered
/// into cubic cells of side `cell`, and each cell's sphere is centred on its points' bounding box,
/// just large enough to hold them. Every point lies inside some sphere, and no sphere reaches more
/// than cell * sqrt(3) / 2 beyond the points it holds. Centres and radii in the points' frame.
struct CoveringSphere {
  Eigen::Vector3d centre;
  double radius = 0.0;
};
std::vector<CoveringSphere> cover_with_spheres(const std::vector<Eigen::Vector3d>& points,
                                               double cell);

}  // namespace lmk
