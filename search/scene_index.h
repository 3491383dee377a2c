// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// SceneIndex: everything the fast search needs from a scene, built once and shared by every
// landmark searched in it (docs/landmarks.md, "The fast search").
//
// - coarse: the scene voxel-downsampled at coarse_leaf, with normals: the candidates' seeds,
//   voting and coarse alignment; its k-d tree is built on first use (the search needs none);
// - field: the distance field of the coarse points (voxel = coarse_leaf), with its closest-point
//   grid: ICP correspondences and the Ceres residuals in O(1);
// - occupancy: the voxels (side leaf_size) that hold a scene point: the empty-space test;
// - range_image: the depth the sensor saw along each ray: projective visibility;
// - fine: the scene at the paper's leaf and its k-d tree, for the metrics that need every point
//   inside a box ("paper", "rapid", "vdb"). It is built on first use.
//
// Thread safety: const after construction; any number of searches may share one index at once
// (the lazy coarse tree and fine level are built under std::call_once).

#include <Eigen/Geometry>
#include <memory>
#include <mutex>
#include <optional>

#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/range_image.h"
#include "lmk/geometry/stop_check.h"
#include "lmk/landmark/scene_settings.h"
#include "lmk/occupancy/distance_field.h"
#include "lmk/occupancy/occupancy_grid.h"

namespace lmk {

/// A frame's range image, built by the first index of that frame and shared by the others
/// (SceneIndex::shared_range_image): a tracker indexes one frame around each of its landmarks, and
/// each index would otherwise build the same image of the whole frame. Null: the frame is no view
/// from its recorded sensor pose.
using FrameImage = std::shared_ptr<const RangeImage>;

/// What earlier work on the same stream or frame spares an index.
struct SceneIndexReuse {
  /// An organised scene's camera intrinsics, already fitted to an earlier frame of the same camera
  /// (RangeImage::from_cloud's `known`): spares the range image its fit.
  const PinholeIntrinsics* intrinsics = nullptr;
  /// This frame's image, from another index of the same scene with the same settings
  /// (shared_range_image; the work volume aside: the image is always the whole frame's). Nothing:
  /// the index builds its own.
  std::optional<FrameImage> image;
};

class SceneIndex {
 public:
  /// Throws lmk::Error for bad settings or a scene (after the crop) without a finite point.
  /// `stop` is called between pieces of the work, here and when the fine level is built
  /// (geometry/stop_check.h): what it throws stops the indexing.
  explicit SceneIndex(const PointCloud& scene, const SceneSettings& settings = {},
                      StopCheck stop = {}, const SceneIndexReuse& reuse = {});

  const SceneSettings& settings() const { return settings_; }  ///< as built: resolved()
  const Eigen::Vector3d& up() const { return up_; }
  const Eigen::Isometry3d& T_scene_sensor() const { return T_scene_sensor_; }
  std::size_t input_points() const { return input_points_; }  ///< finite, after the crop

  const PointCloud& coarse() const { return coarse_; }
  /// The coarse points' k-d tree; built on the first call.
  const KdTree& coarse_tree() const;
  const DistanceField& field() const { return field_; }
  const OccupancyGrid& occupancy() const { return occupancy_; }
  /// What the scene's sensor saw along each ray (the whole scene, before the crop), for
  /// projective visibility; null when the cloud is no view from its recorded sensor pose.
  const RangeImage* range_image() const { return range_image_.get(); }
  /// The same image as a handle, for the frame's other indexes (SceneIndexReuse::image).
  const FrameImage& shared_range_image() const { return range_image_; }
  /// Whether the scene was an organised frame, so that its range image holds the sensor's own
  /// pixels (an unorganised cloud's is projected through assumed intrinsics, and its empty pixels
  /// say nothing of what the sensor measured).
  bool organised() const { return organised_; }
  /// Whether the scene's image carries colour (registered RGB), which the colour term compares.
  bool has_colours() const { return range_image_ && !range_image_->colours().empty(); }
  /// The scene at leaf_size and its tree; built on the first call.
  const PointCloud& fine() const;
  const KdTree& fine_tree() const;

  double seconds_to_build() const { return seconds_; }

 private:
  void build_fine() const;

  SceneSettings settings_;
  Eigen::Vector3d up_;
  Eigen::Isometry3d T_scene_sensor_;
  std::size_t input_points_ = 0;
  /// The points the fine level is built from: the work volume's crop, the prepared frame (its
  /// non-finite points too) or a frame's finite points.
  PointCloud cropped_;
  PointCloud coarse_;
  DistanceField field_;
  OccupancyGrid occupancy_;
  FrameImage range_image_;  ///< shared with the other indexes of the frame (SceneIndexReuse)
  bool organised_ = false;
  double seconds_ = 0.0;
  StopCheck stop_;

  mutable std::once_flag coarse_tree_once_;
  mutable std::unique_ptr<KdTree> coarse_tree_;
  mutable std::once_flag fine_once_;
  mutable PointCloud fine_;
  mutable std::unique_ptr<KdTree> fine_tree_;
};

}  // namespace lmk
