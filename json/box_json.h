// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of a box, written and read here only: its pose's fields and its size,
// {"position": [x, y, z], "quaternion": [w, x, y, z], "size": [sx, sy, sz]}. The .lmk file's
// attributes, box files, search settings (a work volume), evaluation results and lmk serve all
// use it. Header-only and internal, like pose_json.h.

#include <nlohmann/json.hpp>
#include <string>

#include "lmk/geometry/box.h"
#include "lmk/json/pose_json.h"

namespace lmk::detail {

inline nlohmann::json box_to_json(const Box& box) {
  nlohmann::json j = pose_to_json(box.pose);
  j["size"] = vector_to_json(box.size);
  return j;
}

/// A box; `where` names it in messages. Anything but an object is named as what it is, not as a
/// box without its fields (issue #34, finding 5). Pose first, then size: the first field in file
/// order is the one a message names.
inline Box box_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) {
    throw Error(where + ": must be a box {\"position\", \"quaternion\", \"size\"}, not " +
                std::string(j.type_name() == std::string("array") ? "an " : "a ") + j.type_name());
  }
  const Eigen::Isometry3d pose = pose_from_json(j, where);
  return Box(pose, numbers_from_json(json_field(j, "size", where), 3, where + ".size"));
}

}  // namespace lmk::detail
