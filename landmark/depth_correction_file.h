// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Depth-correction files: a camera's fitted depth error (geometry/depth_correction.h), written by
// `lmk calibrate-depth` and read by capture and search on that camera's frames (`lmk capture`,
// `lmk find`, `lmk serve`, lmk_node's ~depth_correction), so that a robot corrects its frames the
// same way at demonstration and at replay.
//
//   {"format": "lmk-depth-correction", "version": 1, "model": "z' = z + D z^2, ...",
//    "image": [640, 480], "cells": [8, 6], "per_metre": [48 numbers, row-major],
//    "correspondences": ..., "rms_before_m": ..., "rms_after_m": ..., "source": "..."}

#include <optional>
#include <string>

#include "lmk/geometry/depth_correction.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

inline constexpr int kDepthCorrectionFormatVersion = 1;

/// Reads and validates a depth-correction file; lmk::Error naming the file and the field.
DepthCalibration load_depth_correction(const std::string& path);

/// The correction in `path`, for a frame source that undoes it on every frame (lmk_node, lmk serve,
/// lmk pbd run --ros); nothing when `path` is empty.
std::optional<DepthCorrection> load_depth_correction_if_given(const std::string& path);

/// Writes `calibration` atomically (validated first).
void save_depth_correction(const std::string& path, const DepthCalibration& calibration);

/// The correction in `path`, applied to `frame` (DepthCorrection::apply); nothing when `path` is
/// empty. The message of a frame it does not fit names the file.
void correct_depth(PointCloud& frame, const std::string& path);

}  // namespace lmk
