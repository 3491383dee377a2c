// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/landmark_index.h"

#include <algorithm>
#include <mutex>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/geometry/voxel_normals.h"
#include "lmk/landmark/detail/point_pair_voting.h"
#include "lmk/landmark/error_metrics.h"

namespace lmk {

struct LandmarkIndex::Lazy {
  std::once_flag empty_once;
  std::vector<float> empty_distances;
};

struct LandmarkIndex::Fast {
  PointCloud coarse;
  double diameter = 0.0;
  double vote_leaf = 0.0;
  std::unique_ptr<const detail::PointPairModel> pairs;
};

LandmarkIndex::LandmarkIndex(std::shared_ptr<const Landmark> landmark, const FindSettings& settings)
    : landmark_(std::move(landmark)) {
  if (!landmark_) throw Error("landmark index: no landmark");
  build(settings);
}

LandmarkIndex::LandmarkIndex(Landmark landmark, const FindSettings& settings)
    : LandmarkIndex(std::make_shared<const Landmark>(std::move(landmark)), settings) {}

LandmarkIndex LandmarkIndex::borrowing(const Landmark& landmark, const FindSettings& settings) {
  return LandmarkIndex(std::shared_ptr<const Landmark>(&landmark, [](const Landmark*) {}),
                       settings);
}

LandmarkIndex::~LandmarkIndex() = default;
LandmarkIndex::LandmarkIndex(LandmarkIndex&&) noexcept = default;
LandmarkIndex& LandmarkIndex::operator=(LandmarkIndex&&) noexcept = default;

void LandmarkIndex::build(const FindSettings& settings) {
  const Stopwatch stopwatch;
  validate(settings);
  const Landmark& landmark = *landmark_;
  const std::string what = "landmark '" + landmark.name + "'";
  landmark.validate(what);
  if (const auto why = degenerate_shape(landmark.points, landmark.settings.leaf_size, what,
                                        landmark.settings.allow_flat)) {
    throw Error(*why);
  }
  method_ = settings.method;
  coarse_leaf_ = settings.scene.coarse_leaf;
  vote_leaf_fraction_ = settings.fast.vote_leaf_fraction;
  tree_ = std::make_unique<KdTree>(landmark.points);
  lazy_ = std::make_unique<Lazy>();

  if (method_ == SearchMethod::fast) {
    auto fast = std::make_unique<Fast>();
    const double leaf = coarse_leaf_;
    fast->coarse = voxel_downsample(landmark.points, leaf);
    // Voting resolution: a fixed fraction of the landmark's size (Drost et al. sample at 5% of the
    // diameter), never finer than the coarse leaf. It bounds the model to a few hundred points
    // whatever the landmark's size, and the scene pairs per seed likewise.
    fast->diameter =
        std::max(static_cast<double>(landmark.points.bounds().diagonal().norm()), 3.0 * leaf);
    fast->vote_leaf = std::max(leaf, fast->diameter * vote_leaf_fraction_);
    // Model and scene reach the voting resolution the same way, from clouds whose normals were
    // estimated alike (VoxelMoments over two-leaf blocks). The capture's own normals, averaged,
    // gave thin parts such as a drawer handle's bar normals the scene never shows: on the
    // paper-x10 preset (400 candidates), precision on unconventional scenes rose from 0.929 to
    // 0.967.
    const PointCloud like_scene =
        downsample_with_normals(landmark.points, leaf, landmark.sensor_origin);
    const PointCloud vote_model =
        fast->vote_leaf > leaf * 1.01 ? voxel_downsample(like_scene, fast->vote_leaf) : like_scene;
    fast->pairs =
        std::make_unique<detail::PointPairModel>(vote_model, fast->vote_leaf, fast->diameter);
    fast_ = std::move(fast);
  }
  seconds_ = stopwatch.seconds();
}

bool LandmarkIndex::suits(const FindSettings& settings, std::string* why) const {
  const bool fast = settings.method == SearchMethod::fast;
  const bool same = settings.method == method_ &&
                    (!fast || (settings.scene.coarse_leaf == coarse_leaf_ &&
                               settings.fast.vote_leaf_fraction == vote_leaf_fraction_));
  if (!same && why) {
    std::ostringstream text;
    text << "the index of landmark '" << landmark_->name << "' was built for method "
         << setting_name(method_);
    if (method_ == SearchMethod::fast) {
      text << ", coarse leaf " << coarse_leaf_ << " m and vote leaf fraction "
           << vote_leaf_fraction_;
    }
    text << "; the search asks for method " << setting_name(settings.method);
    if (fast) {
      text << ", coarse leaf " << settings.scene.coarse_leaf << " m and vote leaf fraction "
           << settings.fast.vote_leaf_fraction;
    }
    *why = text.str();
  }
  return same;
}

const std::vector<float>& LandmarkIndex::empty_distances() const {
  std::call_once(lazy_->empty_once,
                 [this] { lazy_->empty_distances = empty_space_distances(*landmark_, *tree_); });
  return lazy_->empty_distances;
}

const LandmarkIndex::Fast& LandmarkIndex::fast() const {
  if (!fast_) {
    throw Error("landmark index of '" + landmark_->name + "': built for method " +
                setting_name(method_) + ", not fast");
  }
  return *fast_;
}

const PointCloud& LandmarkIndex::coarse() const { return fast().coarse; }
double LandmarkIndex::diameter() const { return fast().diameter; }
double LandmarkIndex::vote_leaf() const { return fast().vote_leaf; }
const detail::PointPairModel& LandmarkIndex::point_pairs() const { return *fast().pairs; }

}  // namespace lmk
