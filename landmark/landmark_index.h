// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// LandmarkIndex: everything a search derives from the landmark alone, built once and shared by
// every search of that landmark (in many scenes, in many frames, on many threads). The landmark's
// counterpart of SceneIndex (docs/landmarks.md, "The fast search").
//
// - tree: the landmark's points in a k-d tree (the metrics' closest points);
// - empty distances: each observed-empty voxel's distance to the nearest landmark point (the
//   sensor metric's empty-space test beyond the distance field's band), built on first use;
// - fast method only: the landmark at the scene's coarse leaf (coarse alignment, the seed
//   spacing), its diameter, and the point pair model it votes with (Drost et al.'s hash table of
//   the landmark's point pair features), which costs more than a search's voting in a small scene.
//
// What it holds depends on three search settings: the method, the scene's coarse leaf and the
// fast method's vote_leaf_fraction. A search with other values refuses the index (suits()). The
// caller owns it: there is no hidden cache, and an edited landmark needs a new index.
//
// Thread safety: const after construction; any number of searches may share one.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/kdtree.h"
#include "lmk/landmark/find_settings.h"
#include "lmk/landmark/landmark.h"

namespace lmk {
namespace detail {
class PointPairModel;
}

class LandmarkIndex {
 public:
  /// Throws lmk::Error for bad settings, an invalid landmark or one whose shape cannot fix a pose
  /// (flat or straight, unless captured with allow_flat).
  explicit LandmarkIndex(std::shared_ptr<const Landmark> landmark,
                         const FindSettings& settings = {});
  explicit LandmarkIndex(Landmark landmark, const FindSettings& settings = {});
  /// The index of a landmark the caller keeps alive for as long as the index: no copy is made.
  static LandmarkIndex borrowing(const Landmark& landmark, const FindSettings& settings = {});
  ~LandmarkIndex();
  LandmarkIndex(LandmarkIndex&&) noexcept;
  LandmarkIndex& operator=(LandmarkIndex&&) noexcept;

  const Landmark& landmark() const { return *landmark_; }
  const KdTree& tree() const { return *tree_; }
  /// Each of landmark().empty_space.centres()' distance to the nearest landmark point, m. Built
  /// on the first call: only the sensor metric needs it.
  const std::vector<float>& empty_distances() const;

  /// Whether a search with `settings` can use this index: the same method, coarse leaf and vote
  /// leaf fraction as it was built for. When not, `why` (if given) says what differs.
  bool suits(const FindSettings& settings, std::string* why = nullptr) const;

  // Fast method only (lmk::Error otherwise).
  /// The landmark voxel-downsampled at the scene's coarse leaf.
  const PointCloud& coarse() const;
  /// The landmark's diameter, at least three coarse leaves, m: the reach of its point pairs.
  double diameter() const;
  /// The point pairs' sampling step, m (vote_leaf_fraction of the diameter, at least the leaf).
  double vote_leaf() const;
  const detail::PointPairModel& point_pairs() const;

  double seconds_to_build() const { return seconds_; }

 private:
  struct Fast;
  void build(const FindSettings& settings);
  const Fast& fast() const;

  std::shared_ptr<const Landmark> landmark_;
  std::unique_ptr<KdTree> tree_;
  struct Lazy;
  std::unique_ptr<Lazy> lazy_;  ///< what is built on first use (behind a pointer: movable)
  SearchMethod method_ = SearchMethod::fast;
  double coarse_leaf_ = 0.0, vote_leaf_fraction_ = 0.0;
  std::unique_ptr<const Fast> fast_;
  double seconds_ = 0.0;
};

}  // namespace lmk
