// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/oriented_bounding_box.h"

#include <CGAL/Simple_cartesian.h>
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

}  // namespace lmk
