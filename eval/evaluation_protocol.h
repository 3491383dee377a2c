// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The evaluation protocol (docs/datasets.md, "Matching and precision/recall"): matching returned
// landmark poses to ground truth, and the paper's precision/recall under its three assumptions.

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <vector>

#include "lmk/geometry/symmetry.h"

namespace lmk {

struct MatchTolerance {
  /// m, between box centres (one inch, as the paper), or between the points of a symmetry's axis
  /// (Symmetry::centre) where it does not pass through the box centre
  double translation = 0.0254;
  double rotation = 0.2618;  ///< rad (15 degrees), modulo the symmetry
};

/// Angle of the rotation from R_truth to R_found, modulo the symmetry. With an axis of revolution
/// a it is the swing angle acos(a . R_rel a), the smallest over every rotation about a
/// (swing-twist decomposition of R_rel = R_truth^T R_found); with an n-fold axis, the smallest
/// angle from R_truth turned by any multiple of 360/n degrees about a.
double rotation_error(const Eigen::Matrix3d& R_truth, const Eigen::Matrix3d& R_found,
                      const Symmetry& symmetry);

/// Distance between the two poses' box centres; with a symmetry whose axis passes elsewhere
/// (Symmetry::centre), between that point of each box instead, which a turn about the axis leaves
/// in place.
double translation_error(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& found,
                         const Symmetry& symmetry);

/// One (scene, landmark) pair: its ground-truth instances and what a method returned.
struct PairInput {
  std::vector<Eigen::Isometry3d> truth;  ///< ground-truth box poses
  std::vector<Eigen::Isometry3d> found;  ///< returned box poses, best (lowest error) first
  Symmetry symmetry;
  bool in_context = true;
  /// Per ground-truth instance (empty: none): an instance the sensor hardly sees. Nobody is blamed
  /// for missing it, and a pose on it is no false positive either: it counts nowhere.
  std::vector<char> ignored;
  bool is_ignored(std::size_t instance) const {
    return instance < ignored.size() && ignored[instance];
  }
};

struct Counts {
  std::size_t tp = 0, fp = 0, fn = 0;
  std::vector<double> translation_errors;  ///< m, of the true positives
  std::vector<double> rotation_errors;     ///< rad, of the true positives
  void add(const Counts& other);
  /// TP / (TP + FP); nothing when nothing was returned (neither 0 nor 1 would be honest).
  std::optional<double> precision() const;
  /// TP / (TP + FN); nothing when there was nothing to find.
  std::optional<double> recall() const;
};

/// For each returned pose, best first, the ground-truth instance it matches under assumptions 1
/// and 2: the nearest one within tolerance not matched by a better pose; nothing for a false
/// positive.
std::vector<std::optional<std::size_t>> assign_matches(const PairInput& pair,
                                                       const MatchTolerance& tolerance = {});

/// Assumptions 1 and 2 for one pair: each returned pose, best first, is a true positive when its
/// centre is within tolerance of a ground-truth instance not already matched (the nearest such) and
/// its rotation error is within tolerance; otherwise a false positive. Unmatched instances are
/// false negatives. Duplicates on one instance therefore count once. Ignored instances and the
/// poses matched to them count nowhere.
Counts count_all_matches(const PairInput& pair, const MatchTolerance& tolerance = {});

/// Assumption 3 for one pair, the best match only: with ground truth, TP if the best match is
/// correct, FP if it is wrong, FN if nothing was returned; without ground truth, FP if anything was
/// returned. Ignored instances are no ground truth to miss, and a best match on one counts nowhere.
Counts count_best_match(const PairInput& pair, const MatchTolerance& tolerance = {});

/// Assumptions 1 and 2 for one pair, split into bins of a per-item quantity (the range, the hidden
/// fraction): matches are assigned as count_all_matches does over the whole pair, then each true
/// positive and false negative counts in its ground-truth instance's bin (truth_bin) and each false
/// positive in its own (found_bin). Bins outside [0, bins) are left out.
std::vector<Counts> count_all_matches_by(const PairInput& pair, const std::vector<int>& truth_bin,
                                         const std::vector<int>& found_bin, int bins,
                                         const MatchTolerance& tolerance = {});

/// The paper's three assumptions over many pairs: 1, all pairs; 2, in-context pairs;
/// 3, in-context pairs, best match only. Index 0 holds assumption 1.
std::array<Counts, 3> count_assumptions(const std::vector<PairInput>& pairs,
                                        const MatchTolerance& tolerance = {});

}  // namespace lmk
