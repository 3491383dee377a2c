// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The report's failure pictures (issue #16): for each pair where an instance was missed or a
// false match accepted, the scene's depth image with the true and the found boxes drawn through
// the sensor's pinhole, so that a researcher sees why in one look.

#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"

namespace lmk {

struct FailurePicture {
  std::string scene, landmark;
  std::size_t missed = 0;       ///< instances not found (ignored ones are not failures)
  std::size_t false_found = 0;  ///< accepted matches on no instance
  std::string caption;          ///< what the picture shows, in words
  std::string svg;              ///< self-contained: the image is an embedded PNG
};

struct FailurePictures {
  std::vector<FailurePicture> pictures;
  std::size_t pairs_with_failures = 0;  ///< all of them, pictured or not
  std::size_t unpictured = 0;  ///< beyond the limit, or no pinhole view (an unorganised cloud)
};

/// The failing pairs of `evaluation` (matches below its threshold, matched as its table does), at
/// most `limit` of them pictured in dataset order, each from its scene file in `dataset_dir`: the
/// depth image at a quarter of its resolution (near bright, far dark, no return black), with each
/// true box in green (dashed when ignored), each correct match in blue and each false match in red,
/// projected through intrinsics fitted to the organised frame (geometry/range_image.h).
FailurePictures failure_pictures(const Evaluation& evaluation, const std::string& dataset_dir,
                                 std::size_t limit = 40);

}  // namespace lmk
