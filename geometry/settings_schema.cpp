// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/settings_schema.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "lmk/geometry/pose.h"

namespace lmk {

std::string SettingInfo::key() const {
  std::string out = name;
  for (char& c : out) {
    if (c == '_') c = '-';
  }
  return out;
}

std::string SettingInfo::flag() const { return "--" + key(); }

bool SettingInfo::answers_to(const std::string& k) const {
  return k == key() || k == name || (!alias.empty() && k == alias);
}

namespace {

// The whole number `text` gives if it fits T; "-1" for an unsigned T is nothing, not wrapped
// around.
template <class T>
std::optional<T> read_whole_number(const std::string& text) {
  const bool digits = !text.empty() && text.find_first_not_of("+-0123456789") == std::string::npos;
  if (!digits || (std::is_unsigned<T>::value && text.find('-') != std::string::npos)) {
    return std::nullopt;
  }
  try {
    std::size_t used = 0;
    if (std::is_unsigned<T>::value) {
      const unsigned long long v = std::stoull(text, &used);
      if (used == text.size() && v <= std::numeric_limits<T>::max()) return static_cast<T>(v);
    } else {
      const long long v = std::stoll(text, &used);
      if (used == text.size() && v >= std::numeric_limits<T>::min() &&
          v <= std::numeric_limits<T>::max())
        return static_cast<T>(v);
    }
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> read_finite_number(const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::uint64_t> read_non_negative_whole(const std::string& text) {
  return read_whole_number<std::uint64_t>(text);
}

namespace settings_detail {
namespace {

// The shortest text that reads back as `v` to 1e-12 (60 for a tilt of pi/3 rad in degrees, not
// 59.99999999999999).
std::string number_text(double v) {
  std::string text;
  for (int digits = 6; digits <= 17; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << v;
    text = out.str();
    if (std::abs(std::strtod(text.c_str(), nullptr) - v) <= 1e-12 * std::abs(v)) break;
  }
  return text;
}

[[noreturn]] void refuse(const SettingInfo& info, const std::string& where,
                         const std::string& value, const std::string& problem) {
  throw Error(where + info.name + " (" + info.flag() + "): " + value + (value.empty() ? "" : " ") +
              problem);
}

[[noreturn]] void unreadable(const SettingInfo& info, const std::string& text,
                             const std::string& expected) {
  throw Error(info.flag() + ": '" + text + "' is not " + expected);
}

// The text's whitespace-separated words.
std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// One finite number, the whole word.
double finite_number(const SettingInfo& info, const std::string& text) {
  const std::optional<double> v = read_finite_number(text);
  if (!v) unreadable(info, text, "a finite number");
  return *v;
}

// A whole number in T's range, with a message that says which way the text is wrong.
template <class T>
T whole_number(const SettingInfo& info, const std::string& text) {
  if (const std::optional<T> v = read_whole_number<T>(text)) return *v;
  if (text.empty() || text.find_first_not_of("+-0123456789") != std::string::npos)
    unreadable(info, text, "a whole number");
  if (std::is_unsigned<T>::value && text.find('-') != std::string::npos)
    unreadable(info, text, "a non-negative whole number");
  unreadable(info, text, "a whole number in range");
}

void check_number(const SettingInfo& info, double v, const std::string& where) {
  const bool low = info.min_exclusive ? !(v > info.min) : !(v >= info.min);
  if (!std::isfinite(v) || low || v > info.max)
    refuse(info, where, number_text(v / info.text_scale), limits(info));
}

}  // namespace

std::string limits(const SettingInfo& info) {
  if (!info.choices.empty()) {
    std::string known;
    for (const std::string& c : info.choices) known += (known.empty() ? "" : ", ") + c;
    return "must be one of " + known;
  }
  // In the unit of the text, as the user wrote the value.
  const std::string unit = info.text_unit.empty() ? "" : " " + info.text_unit;
  const std::string lo = number_text(info.min / info.text_scale);
  const std::string hi = number_text(info.max / info.text_scale);
  const bool has_min = std::isfinite(info.min), has_max = std::isfinite(info.max);
  if (has_min && has_max) {
    return "must be finite and in " + std::string(info.min_exclusive ? "(" : "[") + lo + ", " + hi +
           "]" + unit;
  }
  if (has_min && info.min_exclusive && info.min == 0.0) return "must be positive and finite";
  if (has_min)
    return std::string("must be finite and ") + (info.min_exclusive ? "above " : "at least ") + lo;
  if (has_max) return "must be finite and at most " + hi + unit;
  return "must be finite";
}

void check(const SettingInfo& info, double v, const std::string& where) {
  check_number(info, v, where);
}
void check(const SettingInfo& info, int v, const std::string& where) {
  check_number(info, v, where);
}
void check(const SettingInfo& info, std::size_t v, const std::string& where) {
  check_number(info, static_cast<double>(v), where);
}
void check(const SettingInfo&, bool, const std::string&) {}

void check(const SettingInfo& info, const std::string& v, const std::string& where) {
  if (v.empty() && info.empty_means_default) return;
  if (info.choices.empty()) {
    if (v.empty()) refuse(info, where, "''", "must not be empty");
    return;
  }
  for (const std::string& c : info.choices) {
    if (v == c) return;
  }
  refuse(info, where, "'" + v + "'", limits(info));
}

void check(const SettingInfo& info, const Eigen::Vector3d& v, const std::string& where) {
  // Its length too: 1e308 1e308 0 has finite parts but no finite length to be divided by.
  if (!v.allFinite() || !std::isfinite(v.norm()) || v.norm() < 1e-9) {
    refuse(info, where, "", "must be a finite non-zero vector");
  }
}

void check(const SettingInfo& info, const Box& v, const std::string& where) {
  if (!v.is_valid()) refuse(info, where, "", "needs a finite pose and positive sides");
}

void parse(const SettingInfo& info, const std::string& text, double& out) {
  out = finite_number(info, text) * info.text_scale;
}
void parse(const SettingInfo& info, const std::string& text, int& out) {
  out = whole_number<int>(info, text);
}
void parse(const SettingInfo& info, const std::string& text, std::size_t& out) {
  out = whole_number<std::size_t>(info, text);
}

void parse(const SettingInfo& info, const std::string& text, bool& out) {
  if (text == "true" || text == "1" || text == "on") {
    out = true;
  } else if (text == "false" || text == "0" || text == "off") {
    out = false;
  } else {
    unreadable(info, text, "true or false");
  }
}

void parse(const SettingInfo&, const std::string& text, std::string& out) { out = text; }

void parse(const SettingInfo& info, const std::string& text, Eigen::Vector3d& out) {
  const std::vector<std::string> w = words(text);
  if (w.size() != 3) unreadable(info, text, "three numbers X Y Z");
  for (int i = 0; i < 3; ++i) out[i] = finite_number(info, w[static_cast<std::size_t>(i)]);
}

void parse(const SettingInfo& info, const std::string& text, Box& out) {
  const std::vector<std::string> w = words(text);
  if (w.size() != 6 && w.size() != 9)
    unreadable(info, text, "a box: CX CY CZ SX SY SZ [ROLL PITCH YAW] (m, degrees)");
  double v[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < w.size(); ++i) v[i] = finite_number(info, w[i]);
  const double deg = 3.14159265358979323846 / 180.0;
  out = Box(pose_from_xyz_rpy({v[0], v[1], v[2]}, {v[6] * deg, v[7] * deg, v[8] * deg}),
            {v[3], v[4], v[5]});
}

std::string to_text(const SettingInfo& info, double v) { return number_text(v / info.text_scale); }
std::string to_text(const SettingInfo&, int v) { return std::to_string(v); }
std::string to_text(const SettingInfo&, std::size_t v) { return std::to_string(v); }
std::string to_text(const SettingInfo&, bool v) { return v ? "true" : "false"; }
std::string to_text(const SettingInfo&, const std::string& v) { return v; }

std::string to_text(const SettingInfo&, const Eigen::Vector3d& v) {
  return number_text(v.x()) + " " + number_text(v.y()) + " " + number_text(v.z());
}

std::string to_text(const SettingInfo&, const Box& v) {
  const Eigen::Vector3d c = v.center();
  const Eigen::Vector3d rpy = rpy_from_rotation(v.pose.linear()) * 180.0 / 3.14159265358979323846;
  std::string out;
  for (double x :
       {c.x(), c.y(), c.z(), v.size.x(), v.size.y(), v.size.z(), rpy.x(), rpy.y(), rpy.z()}) {
    out += (out.empty() ? "" : " ") + number_text(x);
  }
  return out;
}

}  // namespace settings_detail
}  // namespace lmk
