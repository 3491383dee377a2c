// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Settings described once. A settings struct lists its fields, each with its name, help line,
// unit and limits, in one static function; validation, JSON, the evaluation cache key,
// `lmk ablate --vary` and the command-line flags all derive from that list, so a new field cannot
// be left out of any of them.
//
// A struct opts in with a static template that hands each field to a visitor:
//
//   struct ScanSettings {
//     double leaf_size = 0.005;
//     template <class Self, class Visit>
//     static void describe(Self& self, Visit&& visit) {
//       visit(SettingInfo("leaf_size", "voxel leaf, m").positive(), self.leaf_size);
//     }
//   };
//
// `Self` is the struct or the const struct. Field types: double, int, std::size_t (which is also
// std::uint64_t on the LP64 platforms lmk builds on), bool, std::string, a scoped enum with names
// (below), and std::optional of double, std::size_t, Eigen::Vector3d and Box (unset: the documented
// default, null in JSON).
//
// A scoped enum is a setting once a free function `setting_names(E)` beside it lists the names of
// its values in order: the flags, the JSON and the cache key write those names, never numbers, and
// the description takes its choices from the same list (SettingInfo::names_of<E>()).

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/error.h"

static_assert(std::is_same<std::size_t, std::uint64_t>::value,
              "settings_schema.h treats std::uint64_t fields as std::size_t");

namespace lmk {

/// One field of a settings struct.
struct SettingInfo {
  SettingInfo(std::string name_in, std::string help_in)
      : name(std::move(name_in)), help(std::move(help_in)) {}

  std::string name;   ///< snake_case: the JSON key; its kebab-case is the flag and the --vary key
  std::string help;   ///< one line, with the unit
  std::string alias;  ///< an older kebab-case name that flags and --vary still accept
  double min = -std::numeric_limits<double>::infinity();  ///< numbers: the least value accepted
  bool min_exclusive = false;                             ///< numbers: min itself is refused
  double max = std::numeric_limits<double>::infinity();   ///< numbers: the largest value accepted
  std::vector<std::string> choices;  ///< strings: the values accepted (empty: any)
  bool empty_means_default = false;  ///< strings: "" is accepted and means the default
  /// The value stored is the text's times this: a flag in degrees for a field in radians.
  double text_scale = 1.0;
  std::string text_unit;  ///< the unit of the text when it differs from the field's
  /// False for fields that say how to run, not what is found (threads): the evaluation cache key
  /// leaves them out.
  bool affects_results = true;

  SettingInfo& positive() { return above(0.0); }
  SettingInfo& above(double v) {
    min = v;
    min_exclusive = true;
    return *this;
  }
  SettingInfo& at_least(double v) {
    min = v;
    min_exclusive = false;
    return *this;
  }
  SettingInfo& at_most(double v) {
    max = v;
    return *this;
  }
  SettingInfo& within(double lo, double hi) {
    at_least(lo);
    max = hi;
    return *this;
  }
  SettingInfo& one_of(std::vector<std::string> values) {
    choices = std::move(values);
    return *this;
  }
  /// The choices of an enum field: the names its setting_names() lists.
  template <class E>
  SettingInfo& names_of() {
    return one_of(setting_names(E{}));
  }
  SettingInfo& or_default() {
    empty_means_default = true;
    return *this;
  }
  SettingInfo& in_degrees() {
    text_scale = 3.14159265358979323846 / 180.0;
    text_unit = "degrees";
    return *this;
  }
  SettingInfo& also(std::string old_name) {
    alias = std::move(old_name);
    return *this;
  }
  SettingInfo& not_affecting_results() {
    affects_results = false;
    return *this;
  }

  std::string key() const;   ///< the kebab-case name: "max-tilt"
  std::string flag() const;  ///< "--max-tilt"
  bool answers_to(const std::string& key_or_alias) const;
};

/// Whether E is an enum with setting names (the overloads below are for those alone).
template <class E>
using IfSettingEnum = std::enable_if_t<std::is_enum<E>::value, int>;

/// The name of an enum setting's value; "" for a value outside its names.
template <class E, IfSettingEnum<E> = 0>
std::string setting_name(E value) {
  const std::vector<std::string>& names = setting_names(value);
  const auto i = static_cast<std::size_t>(value);
  return i < names.size() ? names[i] : std::string();
}

/// The value of an enum setting named `name`; nothing for an unknown name.
template <class E, IfSettingEnum<E> = 0>
std::optional<E> setting_value_named(const std::string& name) {
  const std::vector<std::string>& names = setting_names(E{});
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<E>(i);
  }
  return std::nullopt;
}

/// `text` as one finite number, the whole word ("1e-3"); nothing for "nan", "inf" or "1x".
std::optional<double> read_finite_number(const std::string& text);
/// `text` as a whole number of at least 0 that fits 64 bits; nothing for "-1", "1.5" or "x".
std::optional<std::uint64_t> read_non_negative_whole(const std::string& text);

/// The per-type checks and text parsers the generic functions below dispatch to. Checks throw
/// lmk::Error "<where><name> (--flag): <value> <problem>", where `where` is a prefix such as
/// "find: fast."; parsers throw "--flag: '<text>' <problem>".
namespace settings_detail {

/// The problem with a value, for messages: "must be in [0, 1]".
std::string limits(const SettingInfo& info);

void check(const SettingInfo& info, double v, const std::string& where);
void check(const SettingInfo& info, int v, const std::string& where);
void check(const SettingInfo& info, std::size_t v, const std::string& where);
void check(const SettingInfo& info, bool v, const std::string& where);
void check(const SettingInfo& info, const std::string& v, const std::string& where);
void check(const SettingInfo& info, const Eigen::Vector3d& v, const std::string& where);
void check(const SettingInfo& info, const Box& v, const std::string& where);
template <class E, IfSettingEnum<E> = 0>
void check(const SettingInfo& info, E v, const std::string& where) {
  check(info, setting_name(v), where);  // a value without a name is refused as ''
}
template <class T>
void check(const SettingInfo& info, const std::optional<T>& v, const std::string& where) {
  if (v) check(info, *v, where);
}

void parse(const SettingInfo& info, const std::string& text, double& out);
void parse(const SettingInfo& info, const std::string& text, int& out);
void parse(const SettingInfo& info, const std::string& text, std::size_t& out);
void parse(const SettingInfo& info, const std::string& text, bool& out);
void parse(const SettingInfo& info, const std::string& text, std::string& out);
/// "X Y Z".
void parse(const SettingInfo& info, const std::string& text, Eigen::Vector3d& out);
/// "CX CY CZ SX SY SZ [ROLL PITCH YAW]": centre and sides in m, angles in degrees.
void parse(const SettingInfo& info, const std::string& text, Box& out);
/// An enum by its name; another word is refused with the names.
template <class E, IfSettingEnum<E> = 0>
void parse(const SettingInfo& info, const std::string& text, E& out) {
  const std::optional<E> value = setting_value_named<E>(text);
  if (!value) throw Error(info.flag() + ": '" + text + "' " + limits(info));
  out = *value;
}
template <class T>
void parse(const SettingInfo& info, const std::string& text, std::optional<T>& out) {
  T value{};
  parse(info, text, value);
  out = value;
}

/// The value as parse() reads it back ("60" for a tilt of pi/3 rad); "" for an unset optional.
std::string to_text(const SettingInfo& info, double v);
std::string to_text(const SettingInfo& info, int v);
std::string to_text(const SettingInfo& info, std::size_t v);
std::string to_text(const SettingInfo& info, bool v);
std::string to_text(const SettingInfo& info, const std::string& v);
std::string to_text(const SettingInfo& info, const Eigen::Vector3d& v);
std::string to_text(const SettingInfo& info, const Box& v);
template <class E, IfSettingEnum<E> = 0>
std::string to_text(const SettingInfo&, E v) {
  return setting_name(v);
}
template <class T>
std::string to_text(const SettingInfo& info, const std::optional<T>& v) {
  return v ? to_text(info, *v) : std::string();
}

/// How many words parse() reads: 1, 3 for a vector, 6 to 9 for a box.
template <class T>
std::pair<int, int> word_count(const T&) {
  return {1, 1};
}
inline std::pair<int, int> word_count(const Eigen::Vector3d&) { return {3, 3}; }
inline std::pair<int, int> word_count(const Box&) { return {6, 9}; }
template <class T>
std::pair<int, int> word_count(const std::optional<T>&) {
  return word_count(T{});
}

}  // namespace settings_detail

/// Throws lmk::Error naming the field (after the prefix `where`, "find: fast.") and its flag for
/// the first field out of its limits.
template <class S>
void validate_settings(const S& settings, const std::string& where) {
  S::describe(settings, [&where](const SettingInfo& info, const auto& value) {
    settings_detail::check(info, value, where);
  });
}

/// Sets the field of `settings` whose key or alias is `key` from its text (a flag's value, a
/// --vary value) and checks it. Returns false when `settings` has no such field; throws
/// lmk::Error for text that does not parse or a value out of the field's limits.
template <class S>
bool set_setting_from_text(S& settings, const std::string& key, const std::string& text,
                           const std::string& where) {
  bool found = false;
  S::describe(settings, [&](const SettingInfo& info, auto& value) {
    if (found || !info.answers_to(key)) return;
    found = true;
    auto parsed = value;
    settings_detail::parse(info, text, parsed);
    settings_detail::check(info, parsed, where);
    value = parsed;
  });
  return found;
}

/// The fields of S, as a default-constructed S describes them.
template <class S>
std::vector<SettingInfo> setting_infos() {
  std::vector<SettingInfo> out;
  const S defaults{};
  S::describe(defaults, [&out](const SettingInfo& info, const auto&) { out.push_back(info); });
  return out;
}

}  // namespace lmk
