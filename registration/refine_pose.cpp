// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/refine_pose.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <cmath>
#include <memory>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

// The field and its gradient at a point, in the form Ceres' automatic differentiation needs:
// plain doubles give the value; Jets carry the chain rule through the trilinear gradient.
double field_at(const DistanceField::Sampler& field, const double p[3]) {
  return field.distance(Eigen::Vector3f(static_cast<float>(p[0]), static_cast<float>(p[1]),
                                        static_cast<float>(p[2])));
}

template <typename Scalar, int N>
ceres::Jet<Scalar, N> field_at(const DistanceField::Sampler& field,
                               const ceres::Jet<Scalar, N> p[3]) {
  Eigen::Vector3f gradient;
  const float value =
      field.distance(Eigen::Vector3f(static_cast<float>(p[0].a), static_cast<float>(p[1].a),
                                     static_cast<float>(p[2].a)),
                     &gradient);
  ceres::Jet<Scalar, N> out(value);
  out.v = gradient.x() * p[0].v + gradient.y() * p[1].v + gradient.z() * p[2].v;
  return out;
}

// The pose is parametrised as a rotation (angle-axis) about `pivot` and a translation, both applied
// after the starting pose: x' = R(w) (x0 - pivot) + pivot + t, where x0 is the point moved by the
// start. Rotating about the source's centroid decouples rotation from translation.
template <typename T>
void move(const double* x0, const Eigen::Vector3d& pivot, const T* pose, T* out) {
  const T centred[3] = {T(x0[0] - pivot.x()), T(x0[1] - pivot.y()), T(x0[2] - pivot.z())};
  ceres::AngleAxisRotatePoint(pose, centred, out);
  for (int i = 0; i < 3; ++i) out[i] += T(pivot[i]) + pose[3 + i];
}

struct SurfaceResidual {
  SurfaceResidual(const DistanceField::Sampler& f, const Eigen::Vector3d& x,
                  const Eigen::Vector3d& c)
      : field(f), x0(x), pivot(c) {}
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    T p[3];
    move(x0.data(), pivot, pose, p);
    residual[0] = field_at(field, p);
    return true;
  }
  const DistanceField::Sampler& field;
  Eigen::Vector3d x0, pivot;
};

struct EmptySpaceResidual {
  EmptySpaceResidual(const DistanceField::Sampler& f, const Eigen::Vector3d& x,
                     const Eigen::Vector3d& c, double w, double m)
      : field(f), x0(x), pivot(c), weight(w), margin(m) {}
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    T p[3];
    move(x0.data(), pivot, pose, p);
    const T d = field_at(field, p);
    residual[0] = d < T(margin) ? T(weight) * (T(margin) - d) : T(0.0);
    return true;
  }
  const DistanceField::Sampler& field;
  Eigen::Vector3d x0, pivot;
  double weight, margin;
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
  double pose[6] = {0, 0, 0, 0, 0, 0};
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const auto& x : moved) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SurfaceResidual, 1, 6>(
                                 new SurfaceResidual(field, x, pivot)),
                             make_loss(settings.loss), pose);
  }
  if (settings.empty_space_weight > 0.0) {
    for (const auto& e : empty_space) {
      if (!e.allFinite()) continue;
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<EmptySpaceResidual, 1, 6>(
              new EmptySpaceResidual(field, T_target_source * e.cast<double>(), pivot,
                                     settings.empty_space_weight, settings.empty_space_margin)),
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
