// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/find_settings.h"

#include <algorithm>

#include "lmk/geometry/error.h"

namespace lmk {

std::vector<std::string> search_methods() { return {"fast", "reference"}; }

bool settings_group_affects(const std::string& method, const std::string& group) {
  if (group == "execution") return false;
  if (group == "reference" || group == "fast") return group == method;
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

std::size_t effective_max_seeds(const FindSettings& settings) {
  if (settings.sampling.max_seeds) return *settings.sampling.max_seeds;
  return settings.method == "reference" ? 1000 : 2000;
}

std::string effective_metric(const FindSettings& settings) {
  if (!settings.selection.metric.empty()) return settings.selection.metric;
  return settings.method == "fast" ? "visibility" : "paper";
}

double effective_threshold(const FindSettings& settings) {
  return settings.selection.threshold
             ? *settings.selection.threshold
             : find_error_metric(effective_metric(settings)).default_threshold;
}

}  // namespace lmk
