// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The fast method's own work on a landmark (SearchMethodSteps::prepare(), search_method.h), built
// once per LandmarkIndex: the landmark at the scene's coarse leaf (coarse alignment, the seed
// spacing), its diameter, and the point pair model it votes with (Drost et al.'s hash table of the
// landmark's point pair features), which costs more than a search's voting in a small scene.
// Internal.

#include <memory>
#include <string>

#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/fast/point_pair_voting.h"
#include "lmk/search/search_method.h"

namespace lmk::detail {

class FastLandmark final : public MethodLandmark {
 public:
  FastLandmark(const Landmark& landmark, const FindSettings& settings);

  /// The same coarse leaf and vote leaf fraction.
  bool suits(const FindSettings& settings) const override;
  std::string built_for() const override { return described(coarse_leaf_, vote_leaf_fraction_); }

  /// The landmark voxel-downsampled at the scene's coarse leaf.
  const PointCloud& coarse() const { return coarse_; }
  /// The landmark's diameter, at least three coarse leaves, m: the reach of its point pairs.
  double diameter() const { return diameter_; }
  /// The point pairs' sampling step, m (vote_leaf_fraction of the diameter, at least the leaf).
  double vote_leaf() const { return vote_leaf_; }
  const PointPairModel& point_pairs() const { return *pairs_; }

  /// ", coarse leaf 0.01 m and vote leaf fraction 0.05": what the model depends on, for messages.
  static std::string described(double coarse_leaf, double vote_leaf_fraction);

 private:
  double coarse_leaf_, vote_leaf_fraction_;
  PointCloud coarse_;
  double diameter_ = 0.0, vote_leaf_ = 0.0;
  std::unique_ptr<const PointPairModel> pairs_;
};

/// The fast method's work in `prepared`, a LandmarkIndex built for it.
const FastLandmark& fast_landmark(const LandmarkIndex& prepared);

}  // namespace lmk::detail
