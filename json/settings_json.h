// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of any settings struct described with settings_schema.h: one member per field,
// named as the field, in the field's own unit; an unset optional is null. Header-only and
// internal, like pose_json.h.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lmk/geometry/settings_schema.h"
#include "lmk/json/box_json.h"
#include "lmk/json/pose_json.h"

namespace lmk::detail {

inline nlohmann::json setting_to_json(const Eigen::Vector3d& v) { return vector_to_json(v); }

inline nlohmann::json setting_to_json(const Box& box) { return box_to_json(box); }

template <class T>
nlohmann::json setting_to_json(const T& v) {
  if constexpr (std::is_enum<T>::value) {
    return nlohmann::json(setting_name(v));  // by name: numbers would change with the order
  } else {
    return nlohmann::json(v);
  }
}

template <class T>
nlohmann::json setting_to_json(const std::optional<T>& v) {
  return v ? setting_to_json(*v) : nlohmann::json(nullptr);
}

template <class S>
nlohmann::json settings_to_json(const S& settings) {
  nlohmann::json j = nlohmann::json::object();
  S::describe(settings, [&j](const SettingInfo& info, const auto& value) {
    j[info.name] = setting_to_json(value);
  });
  return j;
}

inline void setting_from_json(const nlohmann::json& j, const std::string& where,
                              Eigen::Vector3d& out) {
  out = numbers_from_json(j, 3, where);
}

inline void setting_from_json(const nlohmann::json& j, const std::string& where, Box& out) {
  out = box_from_json(j, where);
}

template <class T>
void setting_from_json(const nlohmann::json& j, const std::string& where, T& out) {
  if constexpr (std::is_enum<T>::value) {
    if (!j.is_string()) throw Error(where + ": has the wrong type (" + j.type_name() + ")");
    const std::optional<T> value = setting_value_named<T>(j.get<std::string>());
    if (!value) {
      std::string names;
      for (const std::string& n : setting_names(T{})) names += (names.empty() ? "" : ", ") + n;
      throw Error(where + ": '" + j.get<std::string>() + "' must be one of " + names);
    }
    out = *value;
  } else {
    // Integers must be integers of the right sign; a double accepts any number.
    const bool ok =
        std::is_same<T, bool>::value          ? j.is_boolean()
        : std::is_same<T, std::string>::value ? j.is_string()
        : std::is_floating_point<T>::value    ? j.is_number()
        : std::is_unsigned<T>::value
            ? j.is_number_unsigned() || (j.is_number_integer() && j.get<long long>() >= 0)
            : j.is_number_integer();
    if (!ok) throw Error(where + ": has the wrong type (" + std::string(j.type_name()) + ")");
    out = j.get<T>();
  }
}

template <class T>
void setting_from_json(const nlohmann::json& j, const std::string& where, std::optional<T>& out) {
  if (j.is_null()) {
    out.reset();
    return;
  }
  T value{};
  setting_from_json(j, where, value);
  out = value;
}

/// Reads the fields `j` holds into `settings` (those it lacks keep their value) and checks them;
/// an unknown member is an error, so that a misspelt setting is never silently ignored.
template <class S>
void settings_from_json(const nlohmann::json& j, const std::string& where, S& settings) {
  if (!j.is_object()) throw Error(where + ": must be an object");
  std::size_t known = 0;
  S::describe(settings, [&](const SettingInfo& info, auto& value) {
    if (!j.contains(info.name)) return;
    ++known;
    setting_from_json(j.at(info.name), where + "." + info.name, value);
    settings_detail::check(info, value, where + ".");
  });
  if (known == j.size()) return;
  for (const auto& [key, value] : j.items()) {
    bool found = false;
    S::describe(settings, [&, k = key](const SettingInfo& info, const auto&) {
      found = found || info.name == k;
    });
    if (!found) throw Error(where + ": unknown setting '" + key + "'");
  }
}

}  // namespace lmk::detail
