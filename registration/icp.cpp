// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/icp.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/registration/point_to_plane.h"

namespace lmk {

bool KdTreeTarget::nearest(const Eigen::Vector3f& query, Eigen::Vector3f& point,
                           Eigen::Vector3f& normal) const {
  const auto n = tree_.nearest(query);
  if (!n) return false;
  point = cloud_.points[n->index];
  if (cloud_.has_normals()) normal = cloud_.normals[n->index];
  return true;
}

bool DistanceFieldTarget::nearest(const Eigen::Vector3f& query, Eigen::Vector3f& point,
                                  Eigen::Vector3f& normal) const {
  const int index = sampler_.closest(query);
  if (index < 0) return false;
  point = field_.points()[static_cast<std::size_t>(index)];
  if (normals_) normal = (*normals_)[static_cast<std::size_t>(index)];
  return true;
}

void IcpTarget::nearest_all(const std::vector<Eigen::Vector3f>& queries,
                            std::vector<Eigen::Vector3f>& points,
                            std::vector<Eigen::Vector3f>& normals, std::vector<char>& found) const {
  points.resize(queries.size());
  normals.resize(queries.size());
  found.resize(queries.size());
  for (std::size_t k = 0; k < queries.size(); ++k) {
    found[k] = nearest(queries[k], points[k], normals[k]);
  }
}

void DistanceFieldTarget::nearest_all(const std::vector<Eigen::Vector3f>& queries,
                                      std::vector<Eigen::Vector3f>& points,
                                      std::vector<Eigen::Vector3f>& normals,
                                      std::vector<char>& found) const {
  indices_.resize(queries.size());
  sampler_.closest(queries, indices_);
  points.resize(queries.size());
  normals.resize(queries.size());
  found.resize(queries.size());
  for (std::size_t k = 0; k < queries.size(); ++k) {
    const int index = indices_[k];
    found[k] = index >= 0;
    if (index < 0) continue;
    points[k] = field_.points()[static_cast<std::size_t>(index)];
    if (normals_) normals[k] = (*normals_)[static_cast<std::size_t>(index)];
  }
}

namespace {

void check(const IcpSettings& s, const IcpTarget& target) {
  if (s.termination.max_iterations < 1) throw Error("ICP: at least one iteration is needed");
  if (!(s.correspondences.max_distance > 0.0)) {
    throw Error("ICP: the correspondence distance must be positive");
  }
  if (!(s.correspondences.loss.scale > 0.0 && std::isfinite(s.correspondences.loss.scale))) {
    throw Error("ICP: the robust loss scale must be positive and finite");
  }
  if (s.mode == IcpMode::point_to_plane && !target.has_normals()) {
    throw Error("ICP: point-to-plane needs target normals");
  }
}

// One Gauss-Newton system for a small motion (omega, t) applied on the left,
// q' = q + omega x q + t, with the residuals' absolute sum and count.
struct NormalEquations : PointToPlaneSystem {
  double abs_residual_sum = 0.0;
  std::size_t count = 0;
};

}  // namespace

IcpResult icp(const std::vector<Eigen::Vector3f>& source, const IcpTarget& target,
              const Eigen::Isometry3d& T_target_source, const IcpSettings& settings) {
  check(settings, target);
  IcpResult result;
  result.T_target_source = T_target_source;
  const double max_d2 =
      settings.correspondences.max_distance * settings.correspondences.max_distance;
  const bool to_plane = settings.mode == IcpMode::point_to_plane;
  std::vector<Eigen::Vector3f> finite_source;
  finite_source.reserve(source.size());
  for (const auto& s : source) {
    if (s.allFinite()) finite_source.push_back(s);
  }
  // Each step's correspondences, looked up together (IcpTarget::nearest_all).
  std::vector<Eigen::Vector3f> queries, matches, match_normals;
  std::vector<char> found;
  queries.reserve(finite_source.size());

  for (int iteration = 0; iteration <= settings.termination.max_iterations; ++iteration) {
    // The pass after the last step would only measure the error at the final pose.
    const bool last_step_taken =
        iteration == settings.termination.max_iterations || result.converged;
    if (last_step_taken && !settings.measure_final) break;
    NormalEquations eq;
    const Eigen::Isometry3f T = result.T_target_source.cast<float>();
    queries.clear();
    for (const auto& s : finite_source) queries.push_back(T * s);
    target.nearest_all(queries, matches, match_normals, found);
    for (std::size_t k = 0; k < queries.size(); ++k) {
      if (!found[k]) continue;
      const Eigen::Vector3f& q = queries[k];
      const Eigen::Vector3f& n = match_normals[k];
      const Eigen::Vector3d qd = q.cast<double>(), pd = matches[k].cast<double>();
      if ((qd - pd).squaredNorm() > max_d2) continue;
      if (to_plane) {
        if (!n.allFinite()) continue;
        const Eigen::Vector3d nd = n.cast<double>();
        const double r = nd.dot(qd - pd);
        Eigen::Matrix<double, 6, 1> J;
        J << qd.cross(nd), nd;
        eq.add_lower(J, r, settings.correspondences.loss.weight(r));
        eq.abs_residual_sum += std::abs(r);
      } else {
        const Eigen::Vector3d r = qd - pd;
        const double w = settings.correspondences.loss.weight(r.norm());
        // d(q + omega x q + t)/d(omega, t) = [-[q]x, I], row by row.
        for (int axis = 0; axis < 3; ++axis) {
          Eigen::Matrix<double, 6, 1> J = Eigen::Matrix<double, 6, 1>::Zero();
          J.head<3>() = qd.cross(Eigen::Vector3d::Unit(axis));
          J(3 + axis) = 1.0;
          eq.add_lower(J, r[axis], w);
        }
        eq.abs_residual_sum += r.norm();
      }
      ++eq.count;
    }
    result.inliers = eq.count;
    result.final_error = eq.count > 0 ? eq.abs_residual_sum / static_cast<double>(eq.count)
                                      : std::numeric_limits<double>::infinity();
    if (last_step_taken || eq.count < 6) break;

    // Levenberg-style damping keeps planar or linear targets (rank-deficient) from diverging.
    // The sums filled the lower triangle (add_lower), all that the lower LDLT reads.
    Eigen::Matrix<double, 6, 6> A = eq.JtJ;
    A.diagonal().array() += 1e-9 + 1e-6 * A.diagonal().array();
    const Eigen::Matrix<double, 6, 1> delta = A.ldlt().solve(-eq.Jtr);
    if (!delta.allFinite()) break;
    const Eigen::Vector3d omega = delta.head<3>(), t = delta.tail<3>();
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    if (omega.norm() > 0.0)
      step.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).matrix();
    step.translation() = t;
    result.T_target_source = step * result.T_target_source;
    result.iterations = iteration + 1;
    result.converged = t.norm() < settings.termination.translation_tolerance &&
                       omega.norm() < settings.termination.rotation_tolerance;
  }
  result.T_target_source = orthonormalized(result.T_target_source);  // steps compose with drift
  return result;
}

}  // namespace lmk
