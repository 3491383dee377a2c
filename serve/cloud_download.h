// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A scene's points as the page draws them (GET /api/scenes/ID/cloud), written as JSON text a
// piece at a time, so that the server never holds the whole answer: built in memory, 5 million
// points took 1.08 GB and 11 s (issue #34, finding 3).
#include <cstddef>
#include <string>

#include "lmk/serve/scene_store.h"

namespace lmk::serve {

class CloudDownload {
 public:
  /// Every k-th finite point of `scene`, k the smallest that keeps within `max_points` (>= 1).
  CloudDownload(Scene scene, std::size_t max_points);

  std::size_t points() const { return kept_; }
  std::size_t stride() const { return stride_; }

  /// The next piece of the answer, {id, points, stride, unit: "mm", positions: [x, y, z, ...],
  /// colors: [r, g, b, ...] or null}, at most `points_per_piece` points of it; empty once the
  /// whole answer has been written.
  std::string next(std::size_t points_per_piece = 65536);

 private:
  enum class Part { head, positions, between, colors, tail, done };
  // Writes the kept points from cursor_ on, positions or colours, up to `count` of them.
  void write_points(std::string& out, std::size_t count, bool positions);

  Scene scene_;  // holds the cloud while the answer is written
  std::size_t stride_ = 1, kept_ = 0;
  Part part_ = Part::head;
  std::size_t cursor_ = 0, seen_ = 0, written_ = 0;
};

}  // namespace lmk::serve
