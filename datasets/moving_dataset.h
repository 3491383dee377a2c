// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The "moving" preset (issue #48; docs/datasets.md, "Moving landmarks"): frame sequences at the
// Kinect's 30 Hz of a tabletop where a person pushes one object about, 0.5-3 cm per frame, and
// once per sequence carries it away: lifted out of view for a few frames and put down 20-40 cm
// from where it was. The camera stands still, or pans slowly as a robot's head does. Every frame
// is a scene of an ordinary dataset (dataset.json: the object's box while it is in view, none
// while it is carried) and sequences.json says which frames follow which
// (datasets/track_sequences.h).

#include <cstdint>
#include <functional>
#include <string>

#include "lmk/datasets/dataset.h"

namespace lmk {

/// Bumped whenever what the generator writes changes.
inline constexpr int kMovingGeneratorVersion = 1;

struct MovingOptions {
  int seeds = 2;    ///< sequences per object: odd seeds a still camera, even ones panning
  int frames = 60;  ///< frames per sequence (2 s at 30 Hz); 10 to kMaxMovingFrames
  std::uint64_t first_seed = 1;
  bool noise = true;  ///< false renders exact depth
  /// Only these objects (landmark names: bowl, cup, tide_bottle, spray_bottle); empty: all four.
  std::vector<std::string> landmarks;
  /// Called after each frame written, with (frames done, frames in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

inline constexpr int kMaxMovingFrames = 3000;  ///< 100 s at 30 Hz, about 3 GB of frames

/// The landmarks the moving preset pushes about: the benchmark's tabletop objects.
const std::vector<std::string>& moving_landmarks();

/// Writes the sequences into `dir` (created if absent): landmarks/NAME.lmk (each captured in its
/// benchmark demonstration scene, as `lmk gen --preset paper` does), scenes/SEQUENCE-fNNNN.pcd,
/// dataset.json and sequences.json. Deterministic: the same options write the same content.
/// Throws lmk::Error for options out of range, naming the option.
Dataset generate_moving_dataset(const std::string& dir, const MovingOptions& options = {});

}  // namespace lmk
