// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/request_fields.h"

#include "lmk/geometry/error.h"
#include "lmk/json/pose_json.h"
#include "lmk/json/settings_json.h"
#include "lmk/search/internal/find_settings_json.h"
#include "lmk/search/landmark_library.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {

nlohmann::json parse_body(const std::string& body, const std::string& what) {
  if (body.empty()) return nlohmann::json::object();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(body);
  } catch (const nlohmann::json::exception& e) {
    throw bad_request(what + ": the body is not valid JSON (" + e.what() + ")");
  }
  if (!j.is_object()) throw bad_request(what + ": the body must be a JSON object");
  return j;
}

std::string required_string(const nlohmann::json& body, const std::string& key,
                            const std::string& what) {
  if (!body.contains(key))
    throw bad_request(what + ": missing field '" + printable(key, kEchoedBytes) + "'");
  if (!body[key].is_string()) throw bad_request(what + ": " + key + ": must be a string");
  return body[key].get<std::string>();
}

bool optional_bool(const nlohmann::json& body, const std::string& key, bool fallback,
                   const std::string& what) {
  if (!body.contains(key)) return fallback;
  if (!body[key].is_boolean()) throw bad_request(what + ": " + key + ": must be true or false");
  return body[key].get<bool>();
}

double optional_number(const nlohmann::json& body, const std::string& key, double fallback,
                       const std::string& what) {
  if (!body.contains(key)) return fallback;
  if (!body[key].is_number() || !std::isfinite(body[key].get<double>())) {
    throw bad_request(what + ": " + key + ": must be a finite number");
  }
  return body[key].get<double>();
}

Eigen::Vector3d required_point(const nlohmann::json& body, const std::string& key,
                               const std::string& what) {
  if (!body.contains(key))
    throw bad_request(what + ": missing field '" + printable(key, kEchoedBytes) + "'");
  try {
    return lmk::detail::numbers_from_json(body[key], 3, what + ": " + key);
  } catch (const Error& e) {
    throw bad_request(e.what());
  }
}

Box required_box(const nlohmann::json& body, const std::string& key, const std::string& what) {
  if (!body.contains(key))
    throw bad_request(what + ": missing field '" + printable(key, kEchoedBytes) + "'");
  Box box;
  try {
    lmk::detail::setting_from_json(body[key], what + ": " + key, box);
  } catch (const Error& e) {
    throw bad_request(e.what());
  }
  if (!box.is_valid()) throw bad_request(what + ": " + key + ".size: sides must be positive");
  return box;
}

std::vector<std::string> optional_names(const nlohmann::json& body, const std::string& key,
                                        const std::vector<std::string>& all,
                                        const std::string& what, std::size_t most) {
  if (!body.contains(key)) return all;
  const nlohmann::json& v = body[key];
  const std::string expected = what + ": " + key + ": must be an array of names";
  if (!v.is_array()) throw bad_request(expected);
  if (v.size() > most) {
    throw bad_request(what + ": " + key + ": " + std::to_string(v.size()) + " names; at most " +
                      std::to_string(most));
  }
  std::vector<std::string> names;
  for (const auto& n : v) {
    if (!n.is_string()) throw bad_request(expected);
    names.push_back(n.get<std::string>());
  }
  return names;
}

std::vector<Eigen::Isometry3d> optional_poses(const nlohmann::json& body, const std::string& key,
                                              const std::string& what) {
  if (!body.contains(key)) return {};
  const nlohmann::json& v = body[key];
  if (!v.is_array()) throw bad_request(what + ": " + key + ": must be an array of poses");
  std::vector<Eigen::Isometry3d> poses;
  try {
    for (std::size_t i = 0; i < v.size(); ++i) {
      poses.push_back(
          lmk::detail::pose_from_json(v[i], what + ": " + key + "[" + std::to_string(i) + "]"));
    }
  } catch (const Error& e) {
    throw bad_request(e.what());
  }
  return poses;
}

const std::string& checked_name(const std::string& name, const std::string& what) {
  try {
    LandmarkLibrary::check_name(name, what == "program" ? "program id" : "landmark name");
  } catch (const Error& e) {
    throw bad_request(what + ": " + e.what());
  }
  return name;
}

// The settings' one wire form (docs/serve.md, "Settings"): nested by stage in the fields' own
// units, as lmk serve answers with, `lmk find --json` and `lmk eval --json` write, and lmk_node's
// ~find_settings reads. Only the fields to change need be given.
void apply_find_settings(const nlohmann::json& body, const std::string& what,
                         FindSettings& settings) {
  if (!body.contains("settings")) return;
  const nlohmann::json& s = body["settings"];
  if (!s.is_object()) {
    throw bad_request(what +
                      ": settings: must be an object by stage, such as {\"selection\": "
                      "{\"threshold\": 0.004}}");
  }
  try {
    lmk::detail::find_settings_from_json(s, what + ": settings", settings);
    validate(settings);
  } catch (const Error& e) {
    throw bad_request(e.what());
  }
}

}  // namespace lmk::serve
