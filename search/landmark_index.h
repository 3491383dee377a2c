// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// LandmarkIndex: everything a search derives from the landmark alone, built once and shared by
// every search of that landmark (in many scenes, in many frames, on many threads). The landmark's
// counterpart of SceneIndex (docs/landmarks.md, "The fast search").
//
// - tree: the landmark's points in a k-d tree (the metrics' closest points);
// - empty distances: each observed-empty voxel's distance to the nearest landmark point (the
//   sensor metric's empty-space test beyond the distance field's band), built on first use;
// - the search method's own work (SearchMethodSteps::prepare(), search_method.h): for the fast
//   method, the landmark at the scene's coarse leaf, its diameter, and the point pair model it
//   votes with (Drost et al.'s hash table of the landmark's point pair features), which costs more
//   than a search's voting in a small scene; nothing for the reference.
//
// What it holds depends on the method and on what that method's work depends on (the fast one's:
// the scene's coarse leaf and vote_leaf_fraction). A search with other values refuses the index
// (suits()). The caller owns it: there is no hidden cache, and an edited landmark needs a new
// index.
//
// Thread safety: const after construction; any number of searches may share one.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/kdtree.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/find_settings.h"

namespace lmk {
namespace detail {
class MethodLandmark;
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

  /// Whether a search with `settings` can use this index: the same method, and the same settings
  /// that method's work depends on. When not, `why` (if given) says what differs.
  bool suits(const FindSettings& settings, std::string* why = nullptr) const;

  /// The method it was built for, and that method's own work on the landmark (its method reads
  /// it, search_method.h).
  SearchMethod method() const { return method_; }
  const detail::MethodLandmark& method_landmark() const { return *method_landmark_; }

  double seconds_to_build() const { return seconds_; }

 private:
  void build(const FindSettings& settings);

  std::shared_ptr<const Landmark> landmark_;
  std::unique_ptr<KdTree> tree_;
  struct Lazy;
  std::unique_ptr<Lazy> lazy_;  ///< what is built on first use (behind a pointer: movable)
  SearchMethod method_ = SearchMethod::fast;
  std::unique_ptr<const detail::MethodLandmark> method_landmark_;
  double seconds_ = 0.0;
};

}  // namespace lmk
