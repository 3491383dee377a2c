// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of poses that lmk's files and CLI share: {"position":[x,y,z],
// "quaternion":[w,x,y,z]}. Part of lmk::json, the internal header-only library of the JSON forms
// that several modules share (json/CMakeLists.txt): linked privately and never installed, so that
// lmk's public headers never expose nlohmann-json.
//
// Readers take `where`, which names the value in messages ("dataset.json: scenes[0].sensor_pose"),
// and throw lmk::Error as "<where>.<field>: <problem>".

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"

namespace lmk::detail {

inline nlohmann::json vector_to_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// `v`, or null where it is not finite (JSON has no infinity or NaN).
inline nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

inline nlohmann::json pose_to_json(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{"position", vector_to_json(T.translation())},
          {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

inline const nlohmann::json& json_field(const nlohmann::json& j, const std::string& key,
                                        const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw Error(where + ": missing field '" + key + "'");
  return j.at(key);
}

/// Exactly `n` finite numbers.
inline Eigen::VectorXd numbers_from_json(const nlohmann::json& v, std::size_t n,
                                         const std::string& where) {
  const std::string expected = ": must be an array of " + std::to_string(n) + " numbers";
  if (!v.is_array() || v.size() != n) throw Error(where + expected);
  Eigen::VectorXd out(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    if (!v[i].is_number()) throw Error(where + expected);
    out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
  }
  if (!out.allFinite()) throw Error(where + ": holds a non-finite number");
  return out;
}

/// A pose; its quaternion [w, x, y, z] must have unit length (within 1e-3).
inline Eigen::Isometry3d pose_from_json(const nlohmann::json& j, const std::string& where) {
  const Eigen::Vector3d p =
      numbers_from_json(json_field(j, "position", where), 3, where + ".position");
  const Eigen::Vector4d q =
      numbers_from_json(json_field(j, "quaternion", where), 4, where + ".quaternion");
  return pose_from_unit_quaternion(p, q, where, "quaternion");
}

}  // namespace lmk::detail
