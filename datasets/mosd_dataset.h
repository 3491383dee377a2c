// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A real-data dataset from the labelled Kinect frames of the mOSD "learn" set
// (../shared/data/mosd/learn): landmarks cut around labelled objects, searched in rigidly
// transformed copies of their own frame, where the ground truth is the transform itself.

#include <cstdint>
#include <functional>
#include <string>

#include "lmk/datasets/dataset.h"

namespace lmk {

struct MosdOptions {
  int copies = 2;                 ///< transformed copies of each frame
  int max_frames = 0;             ///< use only the first this many frames (by number); 0: all
  std::size_t min_points = 3000;  ///< objects with fewer labelled points are not landmarks
  double margin = 0.015;          ///< free space drawn around an object's bounds, m
  std::uint64_t seed = 1;         ///< of the transforms
  std::function<void(std::size_t, std::size_t)> progress;  ///< (frames done, frames in all)
};

/// Reads learnN.pcd from `mosd_dir` (label 1 is the table and background, labels from 2 objects)
/// and writes into `out_dir`: per object with enough points a landmark (the box: its bounds in
/// the camera frame plus the margin), per frame `copies` scenes moved by a random rigid motion
/// (any turn about the sensor's up axis, a tilt up to 20 degrees, a shift up to 0.3 m; the sensor
/// pose moves with them), and for each landmark an in-context pair with each copy of its frame.
/// Settings follow the set's parts: boxes (0-16), stacked (17-24), occluded (25-32), cylindric
/// (33-44). Other frames may show the same objects unlabelled, so only in-context pairs have known
/// ground truth: evaluate with --pairs in-context. Throws lmk::Error when no learnN.pcd is found.
Dataset generate_mosd_dataset(const std::string& mosd_dir, const std::string& out_dir,
                              const MosdOptions& options = {});

}  // namespace lmk
