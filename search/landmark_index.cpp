// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/landmark_index.h"

#include <mutex>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/search/metrics/error_metrics.h"
#include "lmk/search/search_method.h"

namespace lmk {

struct LandmarkIndex::Lazy {
  std::once_flag empty_once;
  std::vector<float> empty_distances;
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
  tree_ = std::make_unique<KdTree>(landmark.points);
  lazy_ = std::make_unique<Lazy>();
  method_landmark_ = detail::search_method_steps(method_).prepare(landmark, settings);
  seconds_ = stopwatch.seconds();
}

bool LandmarkIndex::suits(const FindSettings& settings, std::string* why) const {
  const bool same = settings.method == method_ && method_landmark_->suits(settings);
  if (!same && why) {
    *why = "the index of landmark '" + landmark_->name + "' was built for method " +
           setting_name(method_) + method_landmark_->built_for() + "; the search asks for method " +
           setting_name(settings.method) +
           detail::search_method_steps(settings.method).prepared_for(settings);
  }
  return same;
}

const std::vector<float>& LandmarkIndex::empty_distances() const {
  std::call_once(lazy_->empty_once,
                 [this] { lazy_->empty_distances = empty_space_distances(*landmark_, *tree_); });
  return lazy_->empty_distances;
}

}  // namespace lmk
