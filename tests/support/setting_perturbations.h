// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Other valid values of any described setting (geometry/settings_schema.h), for tests that must
// cover every field of a settings struct, including fields added later.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/pose.h"
#include "lmk/geometry/settings_schema.h"

namespace lmk::test {

/// Whether `value` passes the field's own checks.
template <class T>
bool accepted(const SettingInfo& info, const T& value) {
  try {
    settings_detail::check(info, value, "test");
    return true;
  } catch (const Error&) {
    return false;
  }
}

template <class T>
bool same(const T& a, const T& b) {
  if constexpr (std::is_same<T, Box>::value) {
    return a.pose.isApprox(b.pose, 0.0) && a.size == b.size;
  } else {
    return a == b;
  }
}

inline std::vector<double> other_numbers(double v) {
  return {v * 1.5 + 1e-3, v * 0.5, v + 1.0, 0.5, 1.0, 0.0};
}

template <class T>
std::vector<T> other_values(const SettingInfo& info, const T& v) {
  std::vector<T> out;
  if constexpr (std::is_same<T, bool>::value) {
    out.push_back(!v);
  } else if constexpr (std::is_same<T, std::string>::value) {
    for (const std::string& c : info.choices) {
      if (c != v) out.push_back(c);
    }
    if (info.choices.empty()) out.push_back(v + "x");
  } else if constexpr (std::is_enum<T>::value) {
    for (const std::string& name : info.choices) out.push_back(*setting_value_named<T>(name));
  } else if constexpr (std::is_same<T, Eigen::Vector3d>::value) {
    out = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0)};
  } else if constexpr (std::is_same<T, Box>::value) {
    out = {Box(pose_from_xyz_rpy({0.1, 0.2, 0.3}, {0, 0, 0.5}), {1, 2, 3}),
           Box(Eigen::Isometry3d::Identity(), {1, 1, 1})};
  } else {
    for (double x : other_numbers(static_cast<double>(v))) {
      if constexpr (std::is_integral<T>::value) x = std::round(x) + (x == v ? 1 : 0);
      if (x >= 0.0 || std::is_signed<T>::value) out.push_back(static_cast<T>(x));
    }
  }
  std::vector<T> valid;
  for (const T& x : out) {
    if (!same(x, v) && accepted(info, x)) valid.push_back(x);
  }
  return valid;
}

/// Valid values other than `v`: for an unset optional, values that set it; for a set one, unset
/// as well.
template <class T>
std::vector<std::optional<T>> other_values(const SettingInfo& info, const std::optional<T>& v) {
  std::vector<std::optional<T>> out;
  if (v) out.push_back(std::nullopt);
  const T base = v ? *v : T{};
  std::vector<T> inner = other_values(info, base);
  if (!v && accepted(info, base)) inner.insert(inner.begin(), base);
  for (const T& x : inner) out.push_back(x);
  return out;
}

}  // namespace lmk::test
