// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Pose hypotheses from point pair features (Drost, Ulrich, Navab & Ilic, CVPR 2010): the fast
// search's seeds, which cover every orientation instead of the paper's identity rotation. Internal.
//
// A point pair feature F(m1, m2) = (|d|, angle(n1, d), angle(n2, d), angle(n1, n2)), d = m2 - m1,
// is invariant to rigid motion. The model's pairs are hashed by quantised F. A scene reference
// point s_r paired with its neighbours s_i looks up the model pairs with the same feature; each
// such (m_r, m_i) proposes that s_r is m_r, up to a rotation alpha about the normal, and votes for
// (m_r, alpha). The best-voted (m_r, alpha) gives a full 6-DoF pose from one reference point.
//
// Two departures from the original, both for clutter on large planes (tables, walls): pairs of
// points on one plane say nothing about a landmark that has relief, so when the landmark has
// enough non-coplanar pairs, coplanar pairs are left out of the model and skipped in the scene;
// and model features are also hashed into the neighbouring bin of any quantity that lies near a
// bin edge, so that noise in the scene's normals does not lose the vote.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/radius_grid.h"

namespace lmk::detail {

/// Two points are a coplanar pair when both normals are within this angle of each other and of
/// perpendicular to the segment joining them (rad, 15 degrees).
inline constexpr double kCoplanarAngle = 15.0 * 3.14159265358979323846 / 180.0;

struct PoseVote {
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  float votes = 0.0f;
};

/// An orientation prior applied while voting: poses that tilt the model's up axis more than
/// acos(min_cos) away from the scene's are no candidates at all, so they cannot crowd the
/// admissible ones out of a seed's few best poses (as the many ways a flat face lies on a table
/// would).
struct TiltLimit {
  Eigen::Vector3f model_up, scene_up;  ///< unit
  float min_cos = -1.0f;

  /// Whether the rotation R_scene_model keeps the model's up axis within the limit.
  bool admits(const Eigen::Matrix3f& R_scene_model) const {
    return (R_scene_model * model_up).dot(scene_up) >= min_cos;
  }
};

class PointPairModel {
 public:
  /// `model` needs normals. `distance_step` quantises |d| (m); pairs longer than `diameter` are
  /// left out.
  PointPairModel(const PointCloud& model, double distance_step, double diameter);

  /// The best-voted poses for the reference scene point `reference` of `scene` (which needs
  /// normals), paired with its neighbours within the model diameter found through `grid` (built
  /// over `scene`). At most
  /// `max_poses`, each with at least `min_fraction` of the best one's votes; with `tilt`, only
  /// poses within its limit.
  void vote(const PointCloud& scene, const RadiusGrid& grid, Index reference, int max_poses,
            double min_fraction, std::vector<PoseVote>& out, const TiltLimit* tilt = nullptr) const;

  std::size_t size() const { return points_.size(); }
  std::size_t pairs() const { return first_votes_.size(); }
  double diameter() const { return diameter_; }
  bool skips_coplanar() const { return skip_coplanar_; }

 private:
  /// Every neighbour pair of the reference point sr (normal nr, Rs taking it to +x) votes for its
  /// matching model pairs' (model point, alpha) bins in `votes`.
  void accumulate_votes(const PointCloud& scene, const std::vector<Neighbor>& neighbours,
                        Index reference, const Eigen::Matrix3f& Rs,
                        std::vector<std::uint32_t>& votes) const;

  std::vector<Eigen::Vector3f> points_;
  std::vector<Eigen::Matrix3f> to_x_axis_;  ///< per model point: rotation taking its normal to +x
  double distance_step_, diameter_;
  bool skip_coplanar_ = false;
  int distance_bins_ = 0;
  /// Entries of key k: [offsets_[k], offsets_[k + 1]); the key one past the key space has none.
  std::vector<std::uint32_t> offsets_;
  /// The model pairs, by key, as the voting reads them (voting_kernels.h: vote_bins): where the
  /// pair's reference point's votes start in the accumulator (model point x alpha bins), and the
  /// pair's angle about x in alpha bins, so that a vote costs a subtraction and no multiplication.
  std::vector<std::uint32_t> first_votes_;
  std::vector<float> alphas_in_bins_;
};

}  // namespace lmk::detail
