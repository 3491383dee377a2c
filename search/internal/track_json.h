// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One tracked landmark of one frame as JSON, the one writer `lmk track --json` and Python's
// lmk.Tracker share (search/tracker.h), in lmk find's pose convention: the matched box's pose
// (position, quaternion) in the frame, as find_result_json.h writes a match's.
//   {"landmark": "cup", "state": "tracking", "seconds": 0.009,
//    "position": [x, y, z], "quaternion": [w, x, y, z], "error": e, "confidence": p or null}
//   {"landmark": "cup", "state": "lost", "seconds": 0.02, "lost_because": "coverage too low"}

#include <nlohmann/json.hpp>

#include "lmk/json/pose_json.h"
#include "lmk/search/tracker.h"

namespace lmk::detail {

inline nlohmann::json tracked_landmark_to_json(const TrackedLandmark& t) {
  nlohmann::json j = {{"landmark", t.name}, {"state", to_string(t.state)}, {"seconds", t.seconds}};
  if (t.match) {
    j.update(pose_to_json(t.match->box.pose));
    j["error"] = t.match->error;
    j["confidence"] = finite_or_null(t.match->confidence.probability);  // none: uncalibrated
  } else {
    j["lost_because"] = to_string(t.lost_because);
  }
  return j;
}

}  // namespace lmk::detail
