// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Frame sequences of a dataset, for tracking (issue #48; docs/datasets.md, "Sequences"): which of
// a dataset's scenes follow each other, which landmark to follow through them, and when the
// landmark was carried away. DIR/sequences.json beside DIR/dataset.json; every frame is a scene of
// the dataset, with its ground truth there (one instance while the landmark is in view, none
// while it is not).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lmk/datasets/dataset.h"

namespace lmk {

inline constexpr int kSequencesFormatVersion = 1;
/// The most sequences one sequences.json lists, and the most frames one sequence tracks: each
/// frame is a search, and counts without bounds were an audit's finding (issue #61, finding 9).
inline constexpr std::size_t kMaxTrackSequences = 1000;
inline constexpr std::size_t kMaxTrackFrames = 10000;

/// The landmark taken away while the camera looks: lifted out of view, or put down elsewhere.
struct Carry {
  std::size_t from = 0;  ///< the first frame it is no longer where it was
  std::size_t back = 0;  ///< the first frame it is in view again at its new place (> from)
};

struct TrackSequence {
  std::string name;
  std::string landmark;             ///< a landmark of the dataset
  std::vector<std::string> frames;  ///< scene names of the dataset, in time order
  std::optional<Carry> carry;       ///< frame indices into `frames`
  /// The ground truth's own uncertainty (real sequences, whose camera poses come from a
  /// reconstruction): the largest PoseCheck of the sequence's frames, reported beside its figures.
  std::optional<PoseCheck> pose_check;
};

/// Reads DIR/sequences.json and checks it against `dataset`: every frame a scene of it, every
/// landmark one of it, a carry inside its sequence. Throws lmk::Error naming the file and field.
std::vector<TrackSequence> load_track_sequences(const std::string& dir, const Dataset& dataset);

/// Whether DIR holds a sequences.json.
bool has_track_sequences(const std::string& dir);

/// Writes DIR/sequences.json atomically, after the same checks.
void save_track_sequences(const std::string& dir, const Dataset& dataset,
                          const std::vector<TrackSequence>& sequences);

}  // namespace lmk
