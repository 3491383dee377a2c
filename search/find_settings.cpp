// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/find_settings.h"

#include <algorithm>
#include <optional>

#include "lmk/geometry/error.h"
#include "lmk/search/search_method.h"

namespace lmk {

const std::vector<std::string>& setting_names(SearchMethod) {
  static const std::vector<std::string> names{"fast", "reference"};
  return names;
}

const std::vector<std::string>& setting_names(Orientations) {
  static const std::vector<std::string> names{"upright", "full"};
  return names;
}

bool settings_group_affects(SearchMethod method, const std::string& group) {
  if (group == "execution") return false;
  // A method's own group is named as the method (FindSettings::fast, ::reference).
  if (const std::optional<SearchMethod> own = setting_value_named<SearchMethod>(group))
    return *own == method;
  return true;
}

void validate(const FindSettings& settings) {
  validate_settings(settings, "find: ");
  for_each_settings_group(settings, [](const char* name, const auto& group) {
    validate_settings(group, std::string("find: ") + name + ".");
  });
  validate(settings.scene);  // the leaves' order
}

void set_find_setting(FindSettings& settings, const std::string& key, const std::string& text) {
  bool found = set_setting_from_text(settings, key, text, "find: ");
  for_each_settings_group(settings, [&](const char* name, auto& group) {
    found = found || set_setting_from_text(group, key, text, std::string("find: ") + name + ".");
  });
  if (found) return;
  std::string known;
  for (const std::string& k : find_setting_keys()) known += (known.empty() ? "" : ", ") + k;
  throw Error("unknown setting '" + key + "' (known: " + known + ")");
}

std::vector<std::string> find_setting_keys(bool results_only) {
  std::vector<std::string> keys;
  const auto add = [&](const std::vector<SettingInfo>& infos) {
    for (const SettingInfo& info : infos) {
      if (!results_only || info.affects_results) keys.push_back(info.key());
    }
  };
  add(setting_infos<FindSettings>());
  const FindSettings defaults;
  for_each_settings_group(defaults, [&add](const char*, const auto& group) {
    add(setting_infos<std::decay_t<decltype(group)>>());
  });
  return keys;
}

FindSettings FindSettings::resolved() const {
  FindSettings r = *this;
  const detail::SearchMethodSteps& steps = detail::search_method_steps(method);
  r.scene = scene.resolved();
  if (!r.sampling.max_seeds) r.sampling.max_seeds = steps.default_max_seeds();
  if (r.selection.metric.empty()) r.selection.metric = steps.default_metric();
  if (!r.selection.threshold)
    r.selection.threshold = find_error_metric(r.selection.metric).default_threshold;
  return r;
}

}  // namespace lmk
