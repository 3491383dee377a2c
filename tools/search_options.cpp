// SPDX-License-Identifier: BSD-3-Clause
// The command-line flags of described settings, one per field: the search's (landmark/
// find_settings.h) and the capture's (CaptureSettings, landmark/landmark.h). The flag is the
// field's kebab-case name, its help line and limits are the description's, and its value is read
// and checked by the same code as `lmk ablate --vary` and the JSON.

#include <cctype>
#include <memory>
#include <optional>
#include <type_traits>

#include "lmk/geometry/error.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/tracker.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

std::string group_title(const std::string& group) {
  if (group == "scene") return "Scene (steps 1-2)";
  if (group == "sampling") return "Seeds (step 3)";
  if (group == "selection") return "Selection (steps 5-6)";
  if (group == "execution") return "Execution";
  if (setting_value_named<SearchMethod>(group)) {
    // A method's own group, named as the method: "Fast method".
    return static_cast<char>(std::toupper(static_cast<unsigned char>(group[0]))) + group.substr(1) +
           " method";
  }
  return "Search";
}

// What a flag takes, for --help.
template <class T>
std::string value_name(const SettingInfo& info, const T&) {
  if constexpr (std::is_same<T, std::string>::value || std::is_enum<T>::value) {
    std::string names;
    for (const std::string& c : info.choices) names += (names.empty() ? "" : "|") + c;
    return names.empty() ? "TEXT" : names;
  } else if constexpr (std::is_floating_point<T>::value) {
    return "NUM";
  } else {
    return "INT";
  }
}
template <class T>
std::string value_name(const SettingInfo& info, const std::optional<T>&) {
  return value_name(info, T{});
}
// A vector or a box: several numbers, which CLI11 counts ("NUM x 3").
inline std::string value_name(const SettingInfo&, const std::optional<Eigen::Vector3d>&) {
  return "NUM";
}
inline std::string value_name(const SettingInfo&, const std::optional<Box>&) { return "NUM"; }

std::string flag_names(const SettingInfo& info) {
  return info.flag() + (info.alias.empty() ? "" : ",--" + info.alias);
}

// One flag bound to `value`, which must outlive the parse, under the --help heading `title`.
// Messages name the field as validation does, after `where`: "find: fast.max_tilt (--max-tilt):".
template <class T>
void add_flag_for(CLI::App* sub, const std::string& title, const std::string& where,
                  const SettingInfo& info, T& value) {
  const std::string unit = info.text_unit.empty() ? "" : " (" + info.text_unit + ")";
  if constexpr (std::is_same<T, bool>::value) {
    sub->add_flag(flag_names(info) + ",!--no-" + info.key(), value,
                  info.help + (value ? " (default: on)" : " (default: off)"))
        ->group(title);
  } else {
    const auto [least, most] = settings_detail::word_count(value);
    CLI::Option* option = sub->add_option_function<std::vector<std::string>>(
        flag_names(info),
        [info, where, &value](const std::vector<std::string>& words) {
          std::string text;
          for (const std::string& w : words) text += (text.empty() ? "" : " ") + w;
          try {
            T parsed = value;
            settings_detail::parse(info, text, parsed);
            settings_detail::check(info, parsed, where);
            value = parsed;
          } catch (const Error& e) {
            throw CLI::ValidationError(e.what());
          }
        },
        info.help + unit);
    option->expected(least, most)->group(title)->type_name(value_name(info, value));
    const std::string shown = settings_detail::to_text(info, value);
    if (!shown.empty()) option->default_str(shown);
  }
}

template <class S>
void add_flags_for(CLI::App* sub, const std::string& group, S& settings) {
  const std::string where = group == "method" ? "find: " : "find: " + group + ".";
  S::describe(settings, [&](const SettingInfo& info, auto& value) {
    add_flag_for(sub, group_title(group), where, info, value);
  });
}

}  // namespace

void add_capture_options(CLI::App* sub, CaptureSettings& settings) {
  CaptureSettings::describe(settings, [&](const SettingInfo& info, auto& value) {
    // The up axis and the base frame are add_up_options's, which `lmk find` shares.
    if (info.name == "up" || info.name == "base_frame") return;
    add_flag_for(sub, "Capture", "capture: ", info, value);
  });
}

void add_track_options(CLI::App* sub, TrackSettings& settings) {
  add_search_options(sub, settings.find, true);
  TrackSettings::describe(settings, [&](const SettingInfo& info, auto& value) {
    add_flag_for(sub, "Tracking", "track: ", info, value);
  });
}

void add_search_options(CLI::App* sub, FindSettings& settings, bool with_execution) {
  add_flags_for(sub, "method", settings);  // --method
  for_each_settings_group(settings, [&](const char* name, auto& group) {
    if (with_execution || std::string(name) != "execution") add_flags_for(sub, name, group);
  });
  // A file, not a setting: read here so that no request to a server can name one
  // (SelectionSettings::calibration).
  sub->add_option_function<std::string>(
         "--calibration,--confidence-calibration",
         [&settings](const std::string& path) {
           settings.selection.calibration =
               std::make_shared<const ConfidenceCalibration>(read_confidence_calibration(path));
         },
         "Confidence calibration file (lmk calibrate-confidence; default: lmk's built-in one)")
      ->group("Selection")
      ->type_name("FILE");
}

}  // namespace lmk::cli
