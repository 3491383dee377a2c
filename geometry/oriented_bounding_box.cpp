// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/oriented_bounding_box.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/min_quadrilateral_2.h>
#include <CGAL/optimal_bounding_box.h>

#include "lmk/geometry/error.h"

namespace lmk {

using Kernel = CGAL::Simple_cartesian<double>;

Box oriented_bounding_box(const PointCloud& cloud, const OrientedBoundingBoxSettings& settings) {
  std::vector<Kernel::Point_3> points;
  points.reserve(cloud.size());
  for (const Eigen::Vector3f& p : cloud.points) {
    if (is_finite(p)) points.emplace_back(p.x(), p.y(), p.z());
  }
  if (points.size() < 4) {
    throw Error("oriented_bounding_box: needs at least 4 finite points, got " +
                std::to_string(points.size()));
  }
  // CGAL returns the rotation R for which the axis-aligned box of {R p} is smallest. The oriented
  // box is that axis-aligned box mapped back by R^T.
  CGAL::Aff_transformation_3<Kernel> rotation;
  CGAL::oriented_bounding_box(points, rotation, CGAL::parameters::random_seed(settings.seed));
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = rotation.m(r, c);

  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& p : points) {
    const Eigen::Vector3d q = R * Eigen::Vector3d(p.x(), p.y(), p.z());
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  Box box;
  // Re-orthonormalise: CGAL's matrix is a rotation up to rounding, and Box needs a proper one.
  Eigen::Matrix3d axes = R.transpose();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  box.pose.linear() = Eigen::Quaterniond(axes).normalized().toRotationMatrix();
  box.pose.translation() = R.transpose() * (0.5 * (lo + hi));
  box.size = hi - lo;
  return box;
}

Box upright_bounding_box(const PointCloud& cloud, const Eigen::Vector4d& plane) {
  const Eigen::Vector3d n = plane.head<3>().normalized();
  // A frame with z = n, so that the footprint is the points' (x, y) there.
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix3d axes;
  axes.col(0) = helper.cross(n).normalized();
  axes.col(1) = n.cross(axes.col(0));
  axes.col(2) = n;
  std::vector<Kernel::Point_2> footprint;
  double height = 0.0;
  for (const Eigen::Vector3f& p : cloud.points) {
    if (!is_finite(p)) continue;
    const Eigen::Vector3d q = axes.transpose() * p.cast<double>();
    const double above = q.z() + plane[3] / plane.head<3>().norm();
    if (above < -0.01) {
      throw Error("upright_bounding_box: a point lies " + std::to_string(-above) +
                  " m below the plane");
    }
    height = std::max(height, above);
    footprint.emplace_back(q.x(), q.y());
  }
  if (footprint.size() < 3) {
    throw Error("upright_bounding_box: needs at least 3 finite points, got " +
                std::to_string(footprint.size()));
  }
  std::vector<Kernel::Point_2> hull;
  CGAL::convex_hull_2(footprint.begin(), footprint.end(), std::back_inserter(hull));
  Eigen::Vector2d centre = Eigen::Vector2d::Zero(), u = Eigen::Vector2d::UnitX();
  Eigen::Vector2d extent = Eigen::Vector2d::Zero();
  if (hull.size() >= 3) {
    std::vector<Kernel::Point_2> r;  // the rectangle's four corners, in order
    CGAL::min_rectangle_2(hull.begin(), hull.end(), std::back_inserter(r));
    const Eigen::Vector2d a(r[0].x(), r[0].y()), b(r[1].x(), r[1].y()), c(r[2].x(), r[2].y());
    u = (b - a).normalized();
    extent = Eigen::Vector2d((b - a).norm(), (c - b).norm());
    centre = 0.5 * (a + c);
  } else {  // collinear footprint: a box of no width along the line
    const Eigen::Vector2d a(hull.front().x(), hull.front().y()),
        b(hull.back().x(), hull.back().y());
    if ((b - a).norm() > 0.0) u = (b - a).normalized();
    extent = Eigen::Vector2d((b - a).norm(), 0.0);
    centre = 0.5 * (a + b);
  }
  const Eigen::Vector3d x = axes * Eigen::Vector3d(u.x(), u.y(), 0.0);
  Box box;
  box.pose.linear().col(0) = x;
  box.pose.linear().col(1) = n.cross(x);
  box.pose.linear().col(2) = n;
  const double base = -plane[3] / plane.head<3>().norm();  // the plane's height along n
  box.pose.translation() = axes * Eigen::Vector3d(centre.x(), centre.y(), base + 0.5 * height);
  box.size = Eigen::Vector3d(extent.x(), extent.y(), height);
  return box;
}

}  // namespace lmk
