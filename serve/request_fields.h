// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading an API request's JSON body: each reader names the field in its ApiError 400, so that a
// script's author sees what to fix ("find: settings.threshold: ...").
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/search/find_settings.h"

namespace lmk::serve {

/// The body as a JSON object; ApiError 400 for anything else. An empty body is {}.
nlohmann::json parse_body(const std::string& body, const std::string& what);

std::string required_string(const nlohmann::json& body, const std::string& key,
                            const std::string& what);
bool optional_bool(const nlohmann::json& body, const std::string& key, bool fallback,
                   const std::string& what);
double optional_number(const nlohmann::json& body, const std::string& key, double fallback,
                       const std::string& what);
Eigen::Vector3d required_point(const nlohmann::json& body, const std::string& key,
                               const std::string& what);
/// A box {position, quaternion [w,x,y,z], size}: a unit quaternion and positive finite sides.
Box required_box(const nlohmann::json& body, const std::string& key, const std::string& what);
/// A list of names, or every name in `all` when the key is absent; more than `most` names is
/// refused before any is read (100,000 landmark names were read whole: issue #61, finding 9).
std::vector<std::string> optional_names(const nlohmann::json& body, const std::string& key,
                                        const std::vector<std::string>& all,
                                        const std::string& what, std::size_t most);

/// A list of poses {position, quaternion [w,x,y,z]}; empty when the key is absent.
std::vector<Eigen::Isometry3d> optional_poses(const nlohmann::json& body, const std::string& key,
                                              const std::string& what);

/// `name` itself when it is a plain name that cannot leave a directory
/// (LandmarkLibrary::check_name, for landmarks and programs alike); ApiError 400 prefixed with
/// `what` otherwise.
const std::string& checked_name(const std::string& name, const std::string& what);

/// Applies body["settings"] to `settings`: the search settings' one wire form, nested by stage in
/// the fields' own units ({"method": "reference", "selection": {"threshold": 0.004}, "fast":
/// {"max_tilt": 0.52}}), as lmk serve answers with and lmk_node's ~find_settings reads. Fields it
/// lacks keep their value; an unknown one is a 400 naming it.
void apply_find_settings(const nlohmann::json& body, const std::string& what,
                         FindSettings& settings);

}  // namespace lmk::serve
