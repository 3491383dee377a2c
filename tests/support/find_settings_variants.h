// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every single-field change of a FindSettings: for each field of each stage (and the method), each
// valid other value, so that tests over "every setting" cover fields added later by themselves.

#include <string>
#include <type_traits>

#include "lmk/search/find_settings.h"
#include "tests/support/setting_perturbations.h"

namespace lmk::test {

/// Calls g(stage) for the stage of `s` called `name` ("" for the top level, which holds method).
template <class G>
void on_stage(FindSettings& s, const std::string& name, G&& g) {
  if (name.empty()) {
    g(s);
    return;
  }
  for_each_settings_group(s, [&](const char* stage, auto& group) {
    if (name == stage) g(group);
  });
}

/// The stage names, "" (the top level) first.
inline std::vector<std::string> stage_names() {
  std::vector<std::string> names = {""};
  FindSettings s;
  for_each_settings_group(s, [&names](const char* stage, auto&) { names.push_back(stage); });
  return names;
}

/// Calls f(stage, info, variant, text) for every field and every valid other value of it, where
/// variant is `base` with that one field changed and text is the value as a flag would give it.
template <class F>
void for_each_variant(const FindSettings& base, F&& f) {
  for (const std::string& stage : stage_names()) {
    FindSettings probe = base;
    on_stage(probe, stage, [&](auto& group) {
      using S = std::decay_t<decltype(group)>;
      std::size_t field = 0;
      S::describe(group, [&](const SettingInfo& info, auto& value) {
        const std::size_t index = field++;
        using Field = std::decay_t<decltype(value)>;
        const auto others = other_values(info, value);
        for (std::size_t n = 0; n < others.size(); ++n) {
          const Field other = others[n];  // a copy: std::vector<bool> hands out proxies
          FindSettings variant = base;
          on_stage(variant, stage, [&](auto& target_group) {
            using T = std::decay_t<decltype(target_group)>;
            if constexpr (std::is_same<S, T>::value) {
              std::size_t k = 0;
              T::describe(target_group, [&](const SettingInfo&, auto& target) {
                using V = std::decay_t<decltype(target)>;
                if constexpr (std::is_same<V, Field>::value) {
                  if (k == index) target = other;
                }
                ++k;
              });
            }
          });
          f(stage, info, variant, settings_detail::to_text(info, other));
        }
      });
    });
  }
}

}  // namespace lmk::test
