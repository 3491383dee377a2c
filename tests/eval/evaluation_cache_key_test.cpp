// SPDX-License-Identifier: BSD-3-Clause
// The evaluation cache key changes with every setting that can change what the chosen method
// finds, and with nothing else, so a new setting can never leave a stale cached result in use.

#include <gtest/gtest.h>

#include "lmk/eval/evaluation.h"
#include "tests/support/find_settings_variants.h"

namespace lmk {
namespace {

// Whether the stage's field can change what `method` finds, as the descriptions declare it.
bool matters(SearchMethod method, const std::string& stage, const SettingInfo& info) {
  return info.affects_results && (stage.empty() || settings_group_affects(method, stage));
}

void expect_key_follows_every_setting(SearchMethod method) {
  FindSettings base;
  base.method = method;
  const std::string key = evaluation_cache_key(base, "dataset");
  std::map<std::string, bool> changed;  // field -> some other value changed the key
  test::for_each_variant(base, [&](const std::string& stage, const SettingInfo& info,
                                   const FindSettings& variant, const std::string& text) {
    const std::string field = (stage.empty() ? "" : stage + ".") + info.name;
    const bool differs = evaluation_cache_key(variant, "dataset") != key;
    if (!matters(method, stage, info)) {
      EXPECT_FALSE(differs) << setting_name(method) << ": " << field << " = '" << text
                            << "' is declared not to matter, yet changes the key";
    }
    changed[field] = changed[field] || differs;
  });
  for (const auto& entry : changed) {
    // Named copies, not structured bindings: C++17 lambdas cannot capture bindings (clang).
    const std::string& field = entry.first;
    const bool differs = entry.second;
    const std::string stage =
        field.find('.') == std::string::npos ? "" : field.substr(0, field.find('.'));
    FindSettings probe;
    bool declared = true;
    test::on_stage(probe, stage, [&](auto& group) {
      std::decay_t<decltype(group)>::describe(group, [&](const SettingInfo& info, const auto&) {
        if ((stage.empty() ? "" : stage + ".") + info.name == field)
          declared = matters(method, stage, info);
      });
    });
    // The evaluation searches every pair without the confidence cut and applies it to the recorded
    // matches afterwards (pair_search): the cached searches serve every cut.
    if (field == "selection.min_confidence") {
      EXPECT_FALSE(differs) << setting_name(method) << ": the confidence cut changes the key";
      continue;
    }
    if (declared) {
      EXPECT_TRUE(differs) << setting_name(method) << ": no change of " << field
                           << " changes the cache key";
    }
  }
  EXPECT_NE(evaluation_cache_key(base, "other dataset"), key);
}

class EachMethodsCacheKey : public ::testing::TestWithParam<SearchMethod> {};

TEST_P(EachMethodsCacheKey, FollowsEverySettingOfTheMethodAndNoOtherMethods) {
  expect_key_follows_every_setting(GetParam());
}

// Every method named in setting_names(SearchMethod), so that a new one is checked too.
std::vector<SearchMethod> every_method() {
  std::vector<SearchMethod> methods;
  for (std::size_t i = 0; i < search_methods().size(); ++i)
    methods.push_back(static_cast<SearchMethod>(i));
  return methods;
}

INSTANTIATE_TEST_SUITE_P(Methods, EachMethodsCacheKey, ::testing::ValuesIn(every_method()),
                         [](const auto& info) { return setting_name(info.param); });

TEST(EvaluationCacheKey, SpellingOutADefaultKeepsTheKey) {
  FindSettings implicit, spelled;
  spelled.selection.metric = "visibility";
  spelled.sampling.max_seeds = 2000;
  spelled.selection.threshold = find_error_metric("visibility").default_threshold;
  spelled.scene.field_band = 2.0 * spelled.scene.coarse_leaf;
  EXPECT_EQ(evaluation_cache_key(implicit, "d"), evaluation_cache_key(spelled, "d"));
}

}  // namespace
}  // namespace lmk
