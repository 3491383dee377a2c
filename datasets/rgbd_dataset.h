// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A dataset of real cross-view pairs from an RGB-D sequence with camera poses (lmk gen --from-rgbd,
// docs/datasets.md "Real RGB-D sequences"): landmarks cut in one frame with user-like boxes
// (user_like_boxes.h), searched in the frames min_gap to max_gap frames away, the ground truth
// from the camera poses, and every pair's poses checked by registering the two whole frames.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lmk/datasets/dataset.h"
#include "lmk/datasets/depth_calibration.h"
#include "lmk/datasets/rgbd_sequence.h"
#include "lmk/datasets/user_like_boxes.h"
#include "lmk/geometry/depth_smoothing.h"

namespace lmk {

struct RgbdDatasetOptions {
  RgbdReadOptions read;
  std::string name;              ///< the dataset's name and setting; default: the folder's
  std::size_t frame_stride = 5;  ///< landmarks and scenes come from every this-many-th frame
  std::size_t min_gap = 10;      ///< a landmark is searched in frames this many frames away,
  std::size_t max_gap = 40;      ///< up to this many
  /// The boxes' side, m. Unset: 0.15 times the median depth of the frames used, within 8-40 cm
  /// (30 cm at 2 m, as a user boxes furniture; 8 cm on a desk at half a metre).
  std::optional<double> box_side;
  std::size_t boxes_per_frame = 6;
  /// Each box is also captured from 2 up to this many views (issue #35): its frame and the used
  /// frames view_gap, then -view_gap, then 2 view_gap... frames away, each registered onto the
  /// first from the camera poses (register_view; import.json records each registration, its
  /// "moved" measured at the first box of the frame). The landmark of k views is named
  /// "<name>-v<k>" (the one-view landmark keeps "<name>"); all of a box's landmarks are searched in
  /// the same scenes, those min_gap to max_gap frames from the nearest of the box's views.
  std::size_t views = 1;
  std::size_t view_gap = 10;  ///< frames between a box's views
  /// Each scene fused from this many consecutive frames of the sequence about its own (issue #46;
  /// occupancy/tsdf_volume.h), moved into its camera frame by the sequence's poses; 1 keeps the
  /// frame itself. The landmarks stay one frame's, as a user cuts them.
  std::size_t fuse = 1;
  /// The landmarks are captured, and checked in their own frame, with this depth smoothing
  /// (CaptureSettings::depth_smoothing, pixels); search them with the same.
  int depth_smoothing = kDefaultDepthSmoothing;
  /// Fit the camera's depth error (datasets/depth_calibration.h) on the frames the dataset does not
  /// use (all but every frame_stride-th), and correct every frame used with it before anything
  /// else reads it.
  bool calibrate_depth = false;
  DepthCalibrationSettings calibration;
  /// A correction fitted beforehand (`lmk calibrate-depth`), applied to every frame used, as with
  /// calibrate_depth; not both.
  std::optional<DepthCalibration> depth_correction;
  /// A pair whose camera poses and the whole-frame registration disagree beyond these, at the
  /// landmark's centre, is left out: its ground truth cannot be trusted to the protocol's 25.4 mm
  /// and 15 degrees. Half of each.
  /// Keep the landmarks the capture check warns match elsewhere in their own frame (or miss
  /// themselves there), as a user who ignores the warning would: their findings say so
  /// (Landmark::findings), for fitting and checking the confidence's capture prior (issue #59).
  /// Off: such boxes are refused, as a careful user redraws them.
  bool keep_warned = false;
  double max_pose_disagreement = 0.0127;                   ///< m
  double max_pose_rotation_disagreement = 0.1309;          ///< rad (7.5 degrees)
  std::function<void(std::size_t, std::size_t)> progress;  ///< (frames done, frames in all)
};

/// What an import did beside the dataset: what it refused and left out, and why.
struct RgbdImport {
  Dataset dataset;
  std::string layout;
  double box_side = 0.0;
  std::size_t boxes = 0;                              ///< boxes the rule drew
  std::map<std::string, std::size_t> refused;         ///< by reason: boxes the capture refused
  std::size_t pairs = 0;                              ///< pairs kept
  std::size_t pairs_left_out = 0;                     ///< beyond the pose-disagreement bound
  std::optional<DepthCalibration> depth_calibration;  ///< the correction applied, if any
};

/// Reads the sequence in `sequence_dir` and writes the dataset into `out_dir` (scenes/*.pcd in each
/// camera's optical frame, landmarks/*.lmk, dataset.json, and import.json: the rule, the
/// refusals and every pair's pose check). Evaluate it with --pairs in-context: the pairs the
/// dataset lists are the ones whose ground truth is known.
RgbdImport generate_rgbd_dataset(const std::string& sequence_dir, const std::string& out_dir,
                                 const RgbdDatasetOptions& options = {});

}  // namespace lmk
