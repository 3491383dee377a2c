// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/ik_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "lmk/geometry/random.h"

namespace lmk {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// The frames of the moving joints and the tip, for FK and the geometric Jacobian in one pass.
struct ChainState {
  Eigen::Isometry3d T_tip;
  std::vector<Eigen::Vector3d> axes, origins;  // each moving joint's axis and origin, root frame
};

ChainState evaluate(const KinematicChain& chain, const std::vector<double>& q) {
  ChainState s;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  std::size_t k = 0;
  for (const ChainJoint& j : chain.joints()) {
    T = T * j.T_parent_joint;
    if (!j.moves()) continue;
    s.axes.push_back(T.linear() * j.axis);
    s.origins.push_back(T.translation());
    if (j.type == "prismatic") {
      T.translate(j.axis * q[k++]);
    } else {
      T.rotate(Eigen::AngleAxisd(q[k++], j.axis));
    }
  }
  s.T_tip = T;
  return s;
}

// Position error (m) and rotation error as an angle-axis vector (rad), target minus current.
Vector6d pose_error(const Eigen::Isometry3d& current, const Eigen::Isometry3d& target) {
  Vector6d e;
  e.head<3>() = target.translation() - current.translation();
  const Eigen::AngleAxisd aa(target.linear() * current.linear().transpose());
  e.tail<3>() = aa.angle() * aa.axis();
  return e;
}

struct Attempt {
  std::vector<double> q;
  double position_error = std::numeric_limits<double>::infinity();
  double rotation_error = std::numeric_limits<double>::infinity();
};

// Keeps q within limits: continuous joints wrap, the others are clamped (optionally not at all,
// to tell a joint-limit failure from a workspace one).
void enforce_limits(const std::vector<JointInfo>& joints, std::vector<double>& q, bool clamp) {
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (joints[i].continuous()) {
      q[i] = std::remainder(q[i], 2.0 * M_PI);
    } else if (clamp) {
      q[i] = std::clamp(q[i], joints[i].lower, joints[i].upper);
    }
  }
}

Attempt descend(const KinematicChain& chain, const std::vector<JointInfo>& joints,
                const Eigen::Isometry3d& target, std::vector<double> q, const IkSettings& s,
                bool clamp) {
  const std::size_t n = q.size();
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, n);
  Attempt best;
  for (int it = 0; it <= s.max_iterations; ++it) {
    const ChainState state = evaluate(chain, q);
    Vector6d e = pose_error(state.T_tip, target);
    const double pos = e.head<3>().norm(), rot = e.tail<3>().norm();
    if (pos + s.rotation_weight * rot <
        best.position_error + s.rotation_weight * best.rotation_error) {
      best = {q, pos, rot};
    }
    if (pos <= s.position_tolerance && rot <= s.rotation_tolerance) break;
    for (std::size_t i = 0; i < n; ++i) {
      if (joints[i].type == "prismatic") {
        J.col(i) << state.axes[i], Eigen::Vector3d::Zero();
      } else {
        J.col(i) << state.axes[i].cross(state.T_tip.translation() - state.origins[i]),
            state.axes[i];
      }
    }
    // Weigh rotation rows so that metres and radians are comparable.
    J.bottomRows<3>() *= s.rotation_weight;
    e.tail<3>() *= s.rotation_weight;
    const Eigen::Matrix<double, 6, 6> A =
        J * J.transpose() + s.damping * s.damping * Eigen::Matrix<double, 6, 6>::Identity();
    const Eigen::VectorXd dq = J.transpose() * A.ldlt().solve(e);
    for (std::size_t i = 0; i < n; ++i) q[i] += dq[static_cast<Eigen::Index>(i)];
    enforce_limits(joints, q, clamp);
  }
  return best;
}

double joint_distance(const std::vector<JointInfo>& joints, const std::vector<double>& a,
                      const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double delta =
        joints[i].continuous() ? std::remainder(a[i] - b[i], 2.0 * M_PI) : a[i] - b[i];
    d += delta * delta;
  }
  return std::sqrt(d);
}

// An upper bound on how far the tip can be from the first moving joint's origin: the lengths of
// every joint offset after it, plus the travel of prismatic joints. Beyond it, no search is needed.
double reach_bound(const KinematicChain& chain, Eigen::Vector3d& first_joint_origin) {
  double reach = 0.0;
  bool started = false;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (const ChainJoint& j : chain.joints()) {
    if (started) reach += j.T_parent_joint.translation().norm();
    if (!started) T = T * j.T_parent_joint;
    if (j.moves() && !started) {
      started = true;
      first_joint_origin = T.translation();
    }
    if (j.type == "prismatic") reach += std::max(std::abs(j.lower), std::abs(j.upper));
  }
  return reach;
}

}  // namespace

namespace {

// The starting joints: the seed, or the middle of each joint's range (0 for continuous joints),
// within the limits; a kBadRequest message instead when the seed does not fit the chain.
std::optional<std::vector<double>> start_joints(const std::vector<JointInfo>& joints,
                                                const std::vector<double>& seed, std::string& why) {
  std::vector<double> start = seed;
  if (start.empty()) {
    for (const JointInfo& j : joints)
      start.push_back(j.continuous() ? 0.0 : 0.5 * (j.lower + j.upper));
  }
  if (start.size() != joints.size()) {
    why = "the seed has " + std::to_string(seed.size()) + " values for " +
          std::to_string(joints.size()) + " joints";
    return std::nullopt;
  }
  enforce_limits(joints, start, true);
  return start;
}

// The solutions from `start` and then from random joints, up to solutions_to_compare of them, and
// the closest failure.
struct Attempts {
  std::vector<Attempt> solutions;
  Attempt closest_failure;
};

Attempts attempt_ik(const KinematicChain& chain, const std::vector<JointInfo>& joints,
                    const Eigen::Isometry3d& T_root_target, const std::vector<double>& start,
                    const IkSettings& s) {
  SplitMix64 rng(s.random_seed);
  Attempts out;
  for (int attempt = 0;
       attempt < s.max_attempts && static_cast<int>(out.solutions.size()) < s.solutions_to_compare;
       ++attempt) {
    const std::vector<double> q0 = attempt == 0 ? start : chain.random_joints(rng);
    Attempt a = descend(chain, joints, T_root_target, q0, s, true);
    if (a.position_error <= s.position_tolerance && a.rotation_error <= s.rotation_tolerance) {
      out.solutions.push_back(std::move(a));
    } else if (a.position_error < out.closest_failure.position_error) {
      out.closest_failure = std::move(a);
    }
    // A solution from the caller's own seed is the nearest we can hope for: stop there.
    if (attempt == 0 && !out.solutions.empty()) break;
  }
  return out;
}

// Why no solution was found: without joint limits, can the chain reach the target at all? That
// tells the two reasons apart.
void explain_failure(const KinematicChain& chain, const std::vector<JointInfo>& joints,
                     const Eigen::Isometry3d& T_root_target, const std::vector<double>& start,
                     const IkSettings& s, const Attempt& closest_failure, IkResult& result) {
  SplitMix64 free_rng(s.random_seed + 1);
  for (int attempt = 0; attempt < s.max_attempts / 3; ++attempt) {
    const Attempt free = descend(chain, joints, T_root_target,
                                 attempt == 0 ? start : chain.random_joints(free_rng), s, false);
    if (free.position_error <= s.position_tolerance &&
        free.rotation_error <= s.rotation_tolerance) {
      result.failure = IkFailure::kJointLimits;
      result.message = "the pose is reachable only outside the joint limits";
      return;
    }
  }
  result.failure = IkFailure::kOutOfWorkspace;
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer),
                "out of the workspace: the closest pose found is %.3f m and %.1f deg away",
                closest_failure.position_error, closest_failure.rotation_error * 180.0 / M_PI);
  result.message = buffer;
}

}  // namespace

IkResult solve_ik(const KinematicChain& chain, const Eigen::Isometry3d& T_root_target,
                  const std::vector<double>& seed, const IkSettings& s) {
  IkResult result;
  const std::vector<JointInfo> joints = chain.moving_joints();
  if (!T_root_target.matrix().allFinite()) {
    result.failure = IkFailure::kBadRequest;
    result.message = "the target pose is not finite";
    return result;
  }
  const std::optional<std::vector<double>> start = start_joints(joints, seed, result.message);
  if (!start) {
    result.failure = IkFailure::kBadRequest;
    return result;
  }

  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  const double reach = reach_bound(chain, origin);
  const double distance = (T_root_target.translation() - origin).norm();
  if (distance > reach) {
    result.failure = IkFailure::kOutOfWorkspace;
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer),
                  "out of the workspace: the target is %.3f m from the first joint, beyond the "
                  "chain's reach of %.3f m",
                  distance, reach);
    result.message = buffer;
    return result;
  }

  const Attempts attempts = attempt_ik(chain, joints, T_root_target, *start, s);
  if (!attempts.solutions.empty()) {
    // The solution nearest the start.
    const Attempt* best = &attempts.solutions.front();
    for (const Attempt& a : attempts.solutions) {
      if (joint_distance(joints, a.q, *start) < joint_distance(joints, best->q, *start)) best = &a;
    }
    result.success = true;
    result.joints = best->q;
    result.position_error = best->position_error;
    result.rotation_error = best->rotation_error;
    return result;
  }
  result.joints = attempts.closest_failure.q;
  result.position_error = attempts.closest_failure.position_error;
  result.rotation_error = attempts.closest_failure.rotation_error;
  explain_failure(chain, joints, T_root_target, *start, s, attempts.closest_failure, result);
  return result;
}

}  // namespace lmk
