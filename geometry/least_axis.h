// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The axis of least spread of a 3x3 covariance (a surface patch's normal) and its three spreads,
// without trigonometry. The scene index asks this of every voxel of every frame; the closed-form
// eigen solver (an atan2, a sine and a cosine, then two eigenvectors where a normal needs one) was
// over half of the normals' time.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <Eigen/LU>        // the determinant
#include <algorithm>
#include <cmath>

namespace lmk {

struct LeastAxis {
  /// The covariance's eigenvalues, increasing.
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();
  /// The unit eigenvector of spread[0], of either sign.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
};

namespace detail {

// The least root of x^3 - p x - q, whose three roots are real (those of a symmetric matrix's
// characteristic polynomial once it is traceless: p = tr(B^2) / 2 >= 0, q = det B). The least
// root lies in [-2 sqrt(p/3), -sqrt(p/3)], between the bound on all roots and the cubic's local
// maximum, where the cubic increases: Halley's method from the left end reaches it in two to four
// steps for a patch of a surface (Newton's took four to six, each step a division), more for a
// double root (points on a line), whose steps only halve the gap. It stops where rounding makes
// the cubic non-negative or its slope non-positive, or a step no longer moves x. Steps are clamped
// to the interval: rounding could otherwise carry one across a pair of roots closer than it
// resolves.
[[gnu::always_inline]] inline double least_root_of_depressed_cubic(double p, double q) {
  const double local_maximum = -std::sqrt(p / 3.0);
  double x = 2.0 * local_maximum;
  for (int step = 0; step < 128; ++step) {
    const double f = (x * x - p) * x - q;
    const double slope = 3.0 * x * x - p;
    if (!(f < 0.0) || !(slope > 0.0)) break;
    const double curvature = 6.0 * x;
    const double next =
        std::min(x - 2.0 * f * slope / (2.0 * slope * slope - f * curvature), local_maximum);
    if (!(next > x)) break;
    x = next;
  }
  return x;
}

}  // namespace detail

/// The spreads of a symmetric `covariance` and its axis of least spread. The least eigenvalue
/// comes from the characteristic cubic of the covariance shifted to zero trace and scaled to unit
/// largest entry (well conditioned whatever the units), the other two from the cubic's root sums,
/// and the axis is the kernel of (covariance - least spread), the largest cross product of two of
/// its rows. Where the two least spreads are equal (points on a line) the axis is any unit vector
/// orthogonal to the largest spread's; where all three are, the x axis. Spreads below about 1e-8
/// of the largest are rounding noise.
inline LeastAxis least_axis(const Eigen::Matrix3d& covariance) {
  LeastAxis out;
  const double mean = covariance.trace() / 3.0;
  Eigen::Matrix3d shifted = covariance;
  shifted.diagonal().array() -= mean;
  const double scale = shifted.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) {  // isotropic (or not finite): every axis is as good as another
    out.spread.setConstant(mean);
    return out;
  }
  shifted *= 1.0 / scale;
  const double p = 0.5 * shifted.squaredNorm();
  const double q = shifted.determinant();
  const double x0 = detail::least_root_of_depressed_cubic(p, q);
  // The largest root from the sum (-x0) and product (x0^2 - p) of the other two; the middle one
  // from the product of all three (q), well conditioned since |x0| and x2 are both at least
  // half the other (the trace is zero).
  const double x2 = 0.5 * (std::sqrt(std::max(0.0, 4.0 * p - 3.0 * x0 * x0)) - x0);
  const double x1 = q / (x0 * x2);
  out.spread = Eigen::Vector3d(x0, x1, x2) * scale + Eigen::Vector3d::Constant(mean);

  shifted.diagonal().array() -= x0;
  const Eigen::Vector3d r0 = shifted.row(0), r1 = shifted.row(1), r2 = shifted.row(2);
  const Eigen::Vector3d crosses[3] = {r0.cross(r1), r0.cross(r2), r1.cross(r2)};
  int best = 0;
  double best_norm = crosses[0].squaredNorm();
  for (int k = 1; k < 3; ++k) {
    const double n = crosses[k].squaredNorm();
    if (n > best_norm) best = k, best_norm = n;
  }
  const Eigen::Vector3d* row = &r0;
  if (r1.squaredNorm() > row->squaredNorm()) row = &r1;
  if (r2.squaredNorm() > row->squaredNorm()) row = &r2;
  const double row_norm = row->squaredNorm();
  // A cross product within 1e-10 of the rows' own scale is rounding's, its direction noise.
  if (best_norm > 1e-20 * row_norm * row_norm) {
    out.axis = crosses[best] / std::sqrt(best_norm);
    return out;
  }
  // A rank-one remainder: the kernel is the plane orthogonal to its largest row, crossed here
  // with the unit axis that row leans on least.
  if (!(row_norm > 0.0)) return out;
  Eigen::Index least = 0;
  row->cwiseAbs().minCoeff(&least);
  out.axis = row->cross(Eigen::Vector3d::Unit(least)).normalized();
  return out;
}

}  // namespace lmk
