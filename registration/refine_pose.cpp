// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/refine_pose.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

// The pose is parametrised as a rotation w (angle-axis) about `pivot` and a translation t, both
// applied after the starting pose: x' = R(w) (x0 - pivot) + pivot + t, where x0 is the point moved
// by the start. Rotating about the source's centroid decouples rotation from translation.
//
// Every residual of one evaluation shares R(w) and the right Jacobian Jr(w) of SO(3), through
// which d(R(w) c)/dw = -R(w) [c]x Jr(w) (Sola, Deray & Atchuthan, "A micro Lie theory", eqs. 143
// and 179): the Jacobians are closed-form, where automatic differentiation carried six
// derivatives through every rotation and cost most of the refinement.
// [v]x, the matrix of v x (.).
Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

class PoseCache {
 public:
  /// R(w) and Jr(w) for the parameters Ceres evaluates at; computed again only when they change
  /// (the solver runs on one thread: callers parallelise over candidates).
  void update(const double* w) {
    if (valid_ && w[0] == w_[0] && w[1] == w_[1] && w[2] == w_[2]) return;
    valid_ = true;
    w_ = Eigen::Vector3d(w[0], w[1], w[2]);
    ceres::AngleAxisToRotationMatrix(w, ceres::ColumnMajorAdapter3x3(R_.data()));
    const double theta2 = w_.squaredNorm();
    const Eigen::Matrix3d W = skew(w_);
    if (theta2 < 1e-12) {  // the series to second order: exact in double precision there
      Jr_ = Eigen::Matrix3d::Identity() - 0.5 * W + W * W / 6.0;
    } else {
      const double theta = std::sqrt(theta2);
      Jr_ = Eigen::Matrix3d::Identity() - (1.0 - std::cos(theta)) / theta2 * W +
            (theta - std::sin(theta)) / (theta2 * theta) * W * W;
    }
  }
  const Eigen::Matrix3d& R() const { return R_; }
  const Eigen::Matrix3d& Jr() const { return Jr_; }

 private:
  bool valid_ = false;
  Eigen::Vector3d w_;
  Eigen::Matrix3d R_, Jr_;
};

// The field distance at one moved point: its value and, when asked, its gradient with respect to
// (w, t) as Ceres' 1x6 row. Ceres evaluates each accepted step twice, its cost first and then its
// Jacobians at the same parameters, so the field's value and gradient (what costs: eight lookups)
// are kept for the last parameters and the second evaluation reads them.
class MovedPoint {
 public:
  MovedPoint(const DistanceField::Sampler& field, PoseCache& cache, const Eigen::Vector3d& x0,
             const Eigen::Vector3d& pivot)
      : field_(field), cache_(cache), centred_(x0 - pivot), pivot_(pivot) {}

  double distance(const double* pose, double* jacobian) {
    if (!std::equal(pose, pose + 6, pose_)) {
      cache_.update(pose);
      const Eigen::Vector3d p =
          cache_.R() * centred_ + pivot_ + Eigen::Vector3d(pose[3], pose[4], pose[5]);
      distance_ = field_.distance(p.cast<float>(), &gradient_);
      std::copy(pose, pose + 6, pose_);
    }
    if (jacobian) {
      cache_.update(pose);
      const Eigen::Vector3d g = gradient_.cast<double>();
      // dD/dw = g^T (-R [c]x Jr) = (c x R^T g)^T Jr; dD/dt = g^T.
      const Eigen::RowVector3d dw =
          centred_.cross(cache_.R().transpose() * g).transpose() * cache_.Jr();
      for (int k = 0; k < 3; ++k) {
        jacobian[k] = dw[k];
        jacobian[3 + k] = g[k];
      }
    }
    return distance_;
  }

 private:
  const DistanceField::Sampler& field_;
  PoseCache& cache_;
  Eigen::Vector3d centred_, pivot_;
  double pose_[6] = {NAN, NAN, NAN, NAN, NAN, NAN};  // never equal: nothing kept yet
  float distance_ = 0.0f;
  Eigen::Vector3f gradient_ = Eigen::Vector3f::Zero();
};

// A source point should lie on the target surface: the residual is the field's distance there.
class SurfaceResidual : public ceres::SizedCostFunction<1, 6> {
 public:
  explicit SurfaceResidual(MovedPoint point) : point_(point) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = point_.distance(parameters[0], jacobians ? jacobians[0] : nullptr);
    return true;
  }

 private:
  mutable MovedPoint point_;  // its kept distance: Ceres evaluates on one thread here
};

// Space the landmark saw empty must stay `margin` clear of the target surface:
// weight * max(0, margin - distance).
class EmptySpaceResidual : public ceres::SizedCostFunction<1, 6> {
 public:
  EmptySpaceResidual(MovedPoint point, double weight, double margin)
      : point_(point), weight_(weight), margin_(margin) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    double* jacobian = jacobians ? jacobians[0] : nullptr;
    const double d = point_.distance(parameters[0], jacobian);
    const bool inside = d < margin_;
    residuals[0] = inside ? weight_ * (margin_ - d) : 0.0;
    if (jacobian) {
      for (int k = 0; k < 6; ++k) jacobian[k] = inside ? -weight_ * jacobian[k] : 0.0;
    }
    return true;
  }

 private:
  mutable MovedPoint point_;  // as SurfaceResidual's
  double weight_, margin_;
};

ceres::LossFunction* make_loss(const RobustLoss& loss) {
  switch (loss.kernel) {
    case RobustKernel::none:
      return nullptr;
    case RobustKernel::huber:
      return new ceres::HuberLoss(loss.scale);
    case RobustKernel::cauchy:
      return new ceres::CauchyLoss(loss.scale);
    case RobustKernel::tukey:
      return new ceres::TukeyLoss(loss.scale);
  }
  return nullptr;
}

}  // namespace

RefineResult refine_pose(const std::vector<Eigen::Vector3f>& source,
                         const DistanceField& target_field,
                         const Eigen::Isometry3d& T_target_source, const RefineSettings& settings,
                         const std::vector<Eigen::Vector3f>& empty_space) {
  if (settings.max_iterations < 1) throw Error("refine: at least one iteration is needed");
  if (!(settings.loss.scale > 0.0 && std::isfinite(settings.loss.scale))) {
    throw Error("refine: the robust loss scale must be positive and finite");
  }
  if (!(settings.empty_space_weight >= 0.0) || !(settings.empty_space_margin > 0.0)) {
    throw Error("refine: the empty-space weight must be >= 0 and its margin positive");
  }
  RefineResult result;
  result.T_target_source = T_target_source;

  std::vector<Eigen::Vector3d> moved;
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  for (const auto& s : source) {
    if (!s.allFinite()) continue;
    moved.push_back(T_target_source * s.cast<double>());
    pivot += moved.back();
  }
  if (moved.size() < 3) return result;  // nothing to refine against
  pivot /= static_cast<double>(moved.size());

  const DistanceField::Sampler field(target_field);
  PoseCache cache;
  double pose[6] = {0, 0, 0, 0, 0, 0};
  // One loss for every surface residual; the problem borrows it.
  const std::unique_ptr<ceres::LossFunction> loss(make_loss(settings.loss));
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const auto& x : moved) {
    problem.AddResidualBlock(new SurfaceResidual(MovedPoint(field, cache, x, pivot)), loss.get(),
                             pose);
  }
  if (settings.empty_space_weight > 0.0) {
    for (const auto& e : empty_space) {
      if (!e.allFinite()) continue;
      const MovedPoint probe(field, cache, T_target_source * e.cast<double>(), pivot);
      problem.AddResidualBlock(
          new EmptySpaceResidual(probe, settings.empty_space_weight, settings.empty_space_margin),
          nullptr, pose);
    }
  }

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = settings.max_iterations;
  options.num_threads = 1;  // callers parallelise over candidates
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  result.initial_cost = summary.initial_cost;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  if (!(summary.final_cost <= summary.initial_cost) || !summary.IsSolutionUsable()) {
    result.final_cost = summary.initial_cost;
    return result;
  }
  result.final_cost = summary.final_cost;
  Eigen::Matrix3d R;
  ceres::AngleAxisToRotationMatrix(pose, ceres::ColumnMajorAdapter3x3(R.data()));
  Eigen::Isometry3d update = Eigen::Isometry3d::Identity();
  update.linear() = R;
  update.translation() = pivot + Eigen::Vector3d(pose[3], pose[4], pose[5]) - R * pivot;
  result.T_target_source = orthonormalized(update * T_target_source);
  return result;
}

}  // namespace lmk
