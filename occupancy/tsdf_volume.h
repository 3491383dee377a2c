// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// TsdfVolume: several depth frames of one scene fused into a truncated signed distance volume
// (Curless and Levoy's weighted average, in a sparse OpenVDB grid; issue #46). Each frame is an
// organised cloud (its own pixels are its depth image) with its pose in a common frame. A voxel
// near a surface holds the projective distance to it, in [-1, 1] truncation widths, averaged over
// the frames that saw it with weights 1 / sigma^2 of the depth noise at their range; a frame that
// saw clearly past a voxel carves it (+1), so a surface one frame measured and another saw through
// is decided by weight. The fused surface is the volume's zero crossing, with normals from its
// gradient, and is searched as one frame with less noise and fewer holes (render()).
//
// Thread safety: const after construction; fuse() runs its loops on the calling arena's threads.

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/pinhole_intrinsics.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// The most frames one fusion takes: a second of a Kinect's frames, and the memory of 30 frames
/// held at once (about 110 MB of 640 x 480 clouds).
inline constexpr std::size_t kMaxFusedFrames = 30;

/// One frame to fuse: an organised cloud (its pixels and its sensor pose, cloud->T_cloud_sensor)
/// and where the cloud's frame lies in the common frame.
struct DepthFrame {
  const PointCloud* cloud = nullptr;
  Eigen::Isometry3d T_common_cloud = Eigen::Isometry3d::Identity();
};

struct FusionSettings {
  /// Side of the volume's voxels, m: the search's leaf, finer than the Kinect's noise at 1.5 m.
  double voxel_size = 0.005;
  /// The truncation band on either side of a measured surface, in depth-noise sigmas at its range
  /// (at least four voxels): wide enough that a true surface's noise stays inside it.
  double truncation_sigmas = 3.0;
  /// The depth noise that sets each measurement's band and weight.
  DepthNoise noise;
  /// The rendered view may grow past the reference frame's image to hold what the other frames saw,
  /// up to this factor in width and in height.
  double max_canvas_growth = 2.0;
  /// The most bytes the volume may take (fusion_bytes()); more is refused before anything is
  /// allocated. `lmk find` gives what the machine has available.
  std::size_t max_bytes = std::numeric_limits<std::size_t>::max();

  /// Throws lmk::Error naming the bad value.
  void validate() const;
};

/// What fusing `frames` will take at its peak, bytes: the volume's leaf nodes (8^3 voxels, a
/// distance and a weight each, and the topology marked per thread), counted from the voxels the
/// frames measured and the shell about them, without allocating any. Counting stops once the
/// estimate passes `limit`, so that a frame of scattered points costs no more to refuse than a
/// small one (issue #61, finding 3). About 16 bytes per distinct leaf while it counts.
std::size_t fusion_bytes(const std::vector<DepthFrame>& frames, const FusionSettings& settings,
                         std::size_t limit = std::numeric_limits<std::size_t>::max());

class TsdfVolume {
 public:
  /// Fuses `frames` (1 to kMaxFusedFrames; each organised, with a pinhole image from its sensor
  /// pose). Throws lmk::Error naming the frame for one that is not, for too many, or when
  /// fusion_bytes() passes settings.max_bytes.
  static TsdfVolume fuse(const std::vector<DepthFrame>& frames, const FusionSettings& settings);

  ~TsdfVolume();
  TsdfVolume(TsdfVolume&&) noexcept;
  TsdfVolume& operator=(TsdfVolume&&) noexcept;

  /// Voxels that some frame observed (weight above 0).
  std::size_t observed_voxels() const;
  double voxel_size() const;
  /// The first frame's intrinsics, fitted to its pixels: the view fuse_frames() renders.
  const PinholeIntrinsics& first_intrinsics() const;

  /// The truncated distance (in band widths, + in front of the surface) and the summed weight at
  /// the voxel nearest to `p` (common frame); nothing where no frame observed it.
  struct Sample {
    float distance = 0.0f;
    float weight = 0.0f;
  };
  std::optional<Sample> sample(const Eigen::Vector3d& p) const;

  /// The zero crossings between observed neighbours, common frame, each with the unit gradient of
  /// the distance as its normal (pointing to free space), in a deterministic order.
  PointCloud surface() const;

  /// The surface as an organised frame seen by a pinhole camera `intrinsics` at `T_common_sensor`:
  /// per pixel the nearest surface point along its ray (each zero crossing splatted over the
  /// pixels its voxel covers), NaN where none; its sensor pose is T_common_sensor.
  PointCloud render(const PinholeIntrinsics& intrinsics,
                    const Eigen::Isometry3d& T_common_sensor) const;

 private:
  struct Grid;
  explicit TsdfVolume(std::unique_ptr<Grid> grid);
  std::unique_ptr<Grid> grid_;
};

/// Several frames of one scene as one frame: fused (TsdfVolume::fuse), rendered from the first
/// frame's sensor with its image grown (at most max_canvas_growth) to hold the surface the other
/// frames saw beyond its edges. The result is in the common frame. One frame is returned as it is,
/// moved into the common frame.
PointCloud fuse_frames(const std::vector<DepthFrame>& frames, const FusionSettings& settings = {});

}  // namespace lmk
