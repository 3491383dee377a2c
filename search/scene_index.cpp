// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/scene_index.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/frame_preparation.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/geometry/voxel_normals.h"
#include "lmk/landmark/landmark.h"

namespace lmk {

const std::vector<std::string>& setting_names(UnseenPoints) {
  static const std::vector<std::string> names{"counted", "outside-image", "no-return"};
  return names;
}

void validate(const SceneSettings& settings) {
  validate_settings(settings, "scene: ");
  if (settings.coarse_leaf < settings.leaf_size) {
    std::ostringstream message;
    message << "scene: the coarse leaf (--coarse-leaf, " << settings.coarse_leaf
            << " m) must be at least the leaf size (--leaf-size, " << settings.leaf_size << " m)";
    throw Error(message.str());
  }
  if (settings.field_band && *settings.field_band < settings.coarse_leaf) {
    throw Error("scene: the distance-field band (--field-band) must be at least the coarse leaf");
  }
  if (settings.field_band && *settings.field_band > kMaxFieldBandLeaves * settings.coarse_leaf) {
    std::ostringstream message;
    message << "scene: the distance-field band (--field-band, " << *settings.field_band
            << " m) must be at most " << kMaxFieldBandLeaves << " coarse leaves ("
            << kMaxFieldBandLeaves * settings.coarse_leaf
            << " m): its memory grows with the band, and a candidate farther from the surface is "
               "hopeless";
    throw Error(message.str());
  }
}

namespace {

// The image of a frame already prepared (prepared_frame), as every index of it holds.
FrameImage image_of_prepared(const PointCloud& frame, const PinholeIntrinsics* intrinsics) {
  std::optional<RangeImage> image =
      RangeImage::from_cloud(frame, {}, kMaxIntrinsicsFitRms, intrinsics);
  return image ? std::make_shared<const RangeImage>(std::move(*image)) : nullptr;
}

}  // namespace

SceneIndex::SceneIndex(const PointCloud& scene, const SceneSettings& settings, StopCheck stop,
                       const SceneIndexReuse& reuse)
    : settings_(settings.resolved()),
      T_scene_sensor_(scene.T_cloud_sensor),
      stop_(std::move(stop)) {
  const Stopwatch stopwatch;
  validate(settings);
  if (!scene.T_cloud_sensor.matrix().allFinite())
    throw Error("scene: the sensor pose is not finite");
  up_ = settings.up ? settings.up->normalized()
                    : default_up(scene.T_cloud_sensor, settings.base_frame);

  // A real frame's veil points go and its depth is smoothed first (geometry/frame_preparation.h),
  // as at capture: nothing else may see the raw frame.
  std::optional<PointCloud> prepared =
      prepared_frame(scene, settings.veil_angle, settings.depth_smoothing, settings.depth_noise());
  const PointCloud& frame = prepared ? *prepared : scene;
  if (stop_) stop_();

  // The grids skip non-finite points themselves, so without a work volume they are built from the
  // frame as it is. So does the fine level's downsample (built on first use, and only for the
  // metrics that read every point): it keeps the prepared frame as it is, or a copy of the finite
  // points of a frame that was not prepared, made beside the grids rather than before them.
  const bool whole_frame = !settings.work_volume;
  if (whole_frame) {
    if (std::none_of(frame.points.begin(), frame.points.end(),
                     [](const Eigen::Vector3f& p) { return is_finite(p); })) {
      throw Error("scene: the scene holds no finite point");
    }
  } else {
    cropped_ = crop(frame, *settings.work_volume);
    if (cropped_.empty()) throw Error("scene: the work volume holds no scene point");
  }
  const PointCloud& source = whole_frame ? frame : cropped_;
  // The grids are built side by side: the range image, the finite points and the occupancy (raw
  // points) beside the voxel moments, then the distance field from the centroids beside the
  // normals, so that neither thread waits on the other's serial steps.
  const DistanceFieldSettings field_settings{settings_.coarse_leaf, *settings_.field_band};
  organised_ = frame.is_organized();
  tbb::parallel_invoke(
      [&] {
        range_image_ = reuse.image ? *reuse.image : image_of_prepared(frame, reuse.intrinsics);
        if (stop_) stop_();
        if (whole_frame && !prepared) cropped_ = remove_non_finite(frame);
        input_points_ = whole_frame && prepared
                            ? static_cast<std::size_t>(std::count_if(
                                  frame.points.begin(), frame.points.end(),
                                  [](const Eigen::Vector3f& p) { return is_finite(p); }))
                            : cropped_.size();
        occupancy_ = OccupancyGrid(source.points, settings.leaf_size, stop_);
      },
      [&] {
        const VoxelMoments moments(source, settings.coarse_leaf, stop_);
        coarse_.points = moments.centroids();
        coarse_.set_unorganized();
        coarse_.T_cloud_sensor = scene.T_cloud_sensor;
        // This thread builds the field (the last task given to parallel_invoke runs on the
        // calling thread at once), which splits into a few slabs; the normals, finely divisible,
        // wait for the other thread and fill in around the field's slowest slab.
        tbb::parallel_invoke(
            [&] {
              // Normals from a block of two leaves (about 2 cm at the default 1 cm): fine enough
              // for a carton's edges, and pooled from the raw points rather than the centroids.
              coarse_.normals = moments.normals(scene.sensor_origin(), stop_);
            },
            [&] { field_ = DistanceField(coarse_.points, field_settings, stop_); });
      });
  if (whole_frame && prepared) cropped_ = std::move(*prepared);  // nothing reads `frame` after this
  seconds_ = stopwatch.seconds();
}

const KdTree& SceneIndex::coarse_tree() const {
  std::call_once(coarse_tree_once_, [this] { coarse_tree_ = std::make_unique<KdTree>(coarse_); });
  return *coarse_tree_;
}

void SceneIndex::build_fine() const {
  std::call_once(fine_once_, [this] {
    fine_ = voxel_downsample(cropped_, settings_.leaf_size, stop_);
    fine_.T_cloud_sensor = T_scene_sensor_;
    // nanoflann's build takes no check: about 0.5 s for the 700 000 fine points of a 5-million
    // point room, checked before and after.
    if (stop_) stop_();
    fine_tree_ = std::make_unique<KdTree>(fine_);
    if (stop_) stop_();
  });
}

const PointCloud& SceneIndex::fine() const {
  build_fine();
  return fine_;
}

const KdTree& SceneIndex::fine_tree() const {
  build_fine();
  return *fine_tree_;
}

}  // namespace lmk
