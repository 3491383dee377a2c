// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of FindSettings: {"method": ..., "scene": {...}, "sampling": {...}, ...}, one
// object per stage, each derived from the stage's description (find_settings.h). Header-only;
// internal/: shared within lmk, not installed.

#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>

#include "lmk/json/settings_json.h"
#include "lmk/search/find_settings.h"

namespace lmk::detail {

/// Every setting of every stage.
inline nlohmann::json find_settings_to_json(const FindSettings& settings) {
  nlohmann::json j = settings_to_json(settings);
  for_each_settings_group(
      settings, [&j](const char* name, const auto& group) { j[name] = settings_to_json(group); });
  return j;
}

/// Only what can change the matches of settings.method: the stages settings_group_affects names,
/// without the fields declared not to affect results. The evaluation's cache key hashes this, so
/// tuning the fast search keeps the cached reference searches, and the reverse.
inline nlohmann::json result_settings_to_json(const FindSettings& settings) {
  nlohmann::json j = settings_to_json(settings);
  for_each_settings_group(settings, [&](const char* name, const auto& group) {
    if (!settings_group_affects(settings.method, name)) return;
    nlohmann::json fields = nlohmann::json::object();
    std::decay_t<decltype(group)>::describe(group, [&](const SettingInfo& info, const auto& v) {
      if (info.affects_results) fields[info.name] = setting_to_json(v);
    });
    j[name] = fields;
  });
  return j;
}

/// Reads what find_settings_to_json wrote into `settings`; stages or fields it lacks keep their
/// value, and unknown ones are errors naming `where`.
inline void find_settings_from_json(const nlohmann::json& j, const std::string& where,
                                    FindSettings& settings) {
  if (!j.is_object()) throw Error(where + ": must be an object");
  nlohmann::json top = nlohmann::json::object();
  for (const auto& item : j.items()) {
    // Named copies, not structured bindings: C++17 lambdas cannot capture bindings (clang).
    const std::string& key = item.key();
    const nlohmann::json& value = item.value();
    bool group_found = false;
    for_each_settings_group(settings, [&](const char* name, auto& group) {
      if (key != name) return;
      group_found = true;
      settings_from_json(value, where + "." + name, group);
    });
    if (!group_found) top[key] = value;
  }
  settings_from_json(top, where, settings);
}

}  // namespace lmk::detail
