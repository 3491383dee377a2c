// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Principal axes of a point set: its mean and the eigen-decomposition of its covariance. Normals
// (the axis of least spread of a neighbourhood) and the landmark shape check (is it flat, is it
// straight) both rest on it.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cstddef>

namespace lmk {

struct PrincipalAxes {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  /// Spread along each axis (covariance eigenvalues, not normalised by the count), increasing.
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();
  /// Column i is the unit axis of spread[i]: column 0 is a plane's normal, column 2 a line's
  /// direction.
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

namespace detail {
// `direct`: Eigen's closed-form 3x3 solver, several times faster than the iterative one but with
// eigenvalue errors of about 1e-8 of the largest, which hides a perfect line.
inline void set_axes(const Eigen::Matrix3d& covariance, bool direct, PrincipalAxes& out) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  if (direct) {
    solver.computeDirect(covariance);
  } else {
    solver.compute(covariance);
  }
  out.spread = solver.eigenvalues();
  out.axes = solver.eigenvectors();
}
}  // namespace detail

/// The covariance (not normalised by the count) of a point set given by its moments about some
/// reference point: the count, the sum of the points and the sum of their outer products.
inline Eigen::Matrix3d covariance_from_moments(double count, const Eigen::Vector3d& sum,
                                               const Eigen::Matrix3d& outer) {
  const Eigen::Vector3d mean = sum / count;
  return outer - count * mean * mean.transpose();
}

/// The principal axes of a point set given by its moments about some reference point: the count,
/// the sum of the points and the sum of their outer products, all relative to that reference (the
/// mean is then relative to it too). Moments add up, so sets can be pooled without their points.
/// Uses the closed-form solver: spreads below about 1e-8 of the largest are noise.
inline PrincipalAxes principal_axes_from_moments(double count, const Eigen::Vector3d& sum,
                                                 const Eigen::Matrix3d& outer) {
  PrincipalAxes out;
  if (!(count > 0.0)) return out;
  out.mean = sum / count;
  detail::set_axes(covariance_from_moments(count, sum, outer), /*direct=*/true, out);
  return out;
}

/// The principal axes of the `count` points point_at(0) ... point_at(count - 1) (each convertible
/// to Eigen::Vector3d), accumulated in double for conditioning.
template <typename PointAt>
PrincipalAxes principal_axes(std::size_t count, PointAt point_at) {
  PrincipalAxes out;
  if (count == 0) return out;
  for (std::size_t i = 0; i < count; ++i) out.mean += point_at(i).template cast<double>();
  out.mean /= static_cast<double>(count);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d d = point_at(i).template cast<double>() - out.mean;
    covariance += d * d.transpose();
  }
  detail::set_axes(covariance, /*direct=*/false, out);
  return out;
}

}  // namespace lmk
