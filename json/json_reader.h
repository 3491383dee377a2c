// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A reader for lmk's JSON files (datasets, programs) that names the file and the offending field
// in every message: "dataset.json: scenes[2].pairs[0]: unknown landmark 'cup'". Header-only and
// internal, like pose_json.h.

#include <nlohmann/json.hpp>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/json/pose_json.h"

namespace lmk::detail {

/// Field paths like scenes[2].pairs[0]: `path`.`field`[`i`].
inline std::string at(const std::string& path, const std::string& field, std::size_t i) {
  return path + (path.empty() ? "" : ".") + field + "[" + std::to_string(i) + "]";
}

class JsonReader {
 public:
  explicit JsonReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw Error(file_ + ": " + (where.empty() ? "" : where + ": ") + problem);
  }

  /// The file's text as JSON; lmk::Error "file: not valid JSON (...)" when it is not.
  nlohmann::json parse(const std::string& text) const {
    try {
      return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      fail("", std::string("not valid JSON (") + e.what() + ")");
    }
  }

  /// "file: where", the context the shared JSON readers prefix to their messages.
  std::string in(const std::string& where) const {
    return file_ + (where.empty() ? "" : ": " + where);
  }

  const nlohmann::json& field(const nlohmann::json& j, const std::string& where,
                              const std::string& key) const {
    return json_field(j, key, in(where));
  }

  std::string text(const nlohmann::json& j, const std::string& where,
                   const std::string& key) const {
    const nlohmann::json& v = field(j, where, key);
    if (!v.is_string() || v.get<std::string>().empty()) {
      fail(where, "'" + key + "' must be a non-empty string");
    }
    // Names and paths are printed: one with a control character could rewrite a terminal.
    if (!is_printable_text(v.get<std::string>())) {
      fail(where, "'" + key + "' must be printable text, not '" +
                      printable(v.get<std::string>(), kEchoedBytes) + "'");
    }
    return v.get<std::string>();
  }

  Eigen::VectorXd numbers(const nlohmann::json& v, const std::string& where, std::size_t n) const {
    return numbers_from_json(v, n, in(where));
  }

  Eigen::Isometry3d pose(const nlohmann::json& j, const std::string& where) const {
    return pose_from_json(j, in(where));
  }

  /// The file's "version" must be exactly `expected`.
  void require_version(const nlohmann::json& j, int expected, const std::string& what) const {
    const nlohmann::json& version = field(j, "", "version");
    if (!version.is_number_integer()) {
      fail("version", "must be a whole number such as " + std::to_string(expected) + ", not " +
                          version.dump());
    }
    if (version.get<int>() != expected) {
      fail("version", what + " format version " + version.dump() +
                          " is not supported (this lmk reads " + std::to_string(expected) + ")");
    }
  }

 private:
  std::string file_;
};

}  // namespace lmk::detail
