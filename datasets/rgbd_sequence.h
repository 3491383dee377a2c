// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Real RGB-D sequences with camera poses, in the layouts public data comes in (docs/datasets.md,
// "Real RGB-D sequences"):
//
//   frames   frame-NNNNNN.depth.png, frame-NNNNNN.pose.txt (4 x 4 camera-to-world) and
//            optionally frame-NNNNNN.color.png, with camera-intrinsics.txt or intrinsics.K.txt:
//            7-Scenes, and 3DMatch's SUN3D and 7-Scenes frame triples (../shared/data/real)
//   tum      TUM RGB-D: depth.txt and rgb.txt (timestamp file), groundtruth.txt (timestamp tx ty
//            tz qx qy qz qw), optionally associations.txt; depth in 1/5000 m
//   bop      BOP: scene_camera.json (cam_K, depth_scale, cam_R_w2c, cam_t_w2c in mm) with
//            depth/NNNNNN.png and rgb/NNNNNN.png
//
// Every frame has a depth image, its intrinsics, its camera pose in the sequence's world frame
// and, where the layout registers it to depth, a colour image.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/depth_image.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct RgbdFrame {
  std::string name;         ///< "frame-000150", the TUM timestamp, the BOP image id
  std::string depth_file;   ///< absolute or relative to the working directory
  std::string colour_file;  ///< empty: no colour registered to the depth image
  PinholeIntrinsics intrinsics;
  double metres_per_unit = 0.001;                                    ///< of the depth image
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();  ///< optical frame
};

struct RgbdSequence {
  std::string layout;             ///< "frames", "tum" or "bop"
  std::vector<RgbdFrame> frames;  ///< in the sequence's order
};

/// What a caller may say about a sequence that its files do not.
struct RgbdReadOptions {
  /// Overrides the intrinsics file (and is needed for TUM, which ships none).
  std::optional<PinholeIntrinsics> intrinsics;
  /// Whether the colour images are registered to depth, pixel for pixel. Unset: as the layout
  /// defines it, which is registered for TUM and BOP, and not for the frames layout, because
  /// 7-Scenes never registered its two cameras (3DMatch's SUN3D frames are: say so).
  std::optional<bool> colour_registered;
  /// TUM: a depth frame and the nearest pose (or colour image) must be this close in time, s.
  double max_time_difference = 0.02;
};

/// Reads the sequence in `dir`, recognising its layout by its files. lmk::Error names the file and
/// the problem: no known layout, a missing or unreadable pose, intrinsics or image list, a pose
/// that is not a rigid motion, a frame without a pose.
RgbdSequence read_rgbd_sequence(const std::string& dir, const RgbdReadOptions& options = {});

/// One frame as an organised cloud in its camera's optical frame (the sensor at the origin), with
/// colour where registered. lmk::Error names the image that cannot be read.
PointCloud load_rgbd_frame(const RgbdFrame& frame);

}  // namespace lmk
