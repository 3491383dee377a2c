// SPDX-License-Identifier: BSD-3-Clause
// FindSettings: every field of every stage reaches the JSON, the text form of its flag and the
// validation, through the one description each stage gives of its fields.

#include "lmk/search/find_settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <type_traits>

#include "lmk/search/internal/find_settings_json.h"
#include "tests/support/find_settings_variants.h"

namespace lmk {
namespace {

using nlohmann::json;

// Numbers equal to 1e-9 (angles go through degrees and boxes through roll, pitch and yaw).
bool near(const json& a, const json& b) {
  if (a.is_number() && b.is_number())
    return std::abs(a.get<double>() - b.get<double>()) <= 1e-9 * (1.0 + std::abs(a.get<double>()));
  if (a.type() != b.type() || a.size() != b.size()) return false;
  if (a.is_object()) {
    for (const auto& [key, value] : a.items()) {
      if (!b.contains(key) || !near(value, b.at(key))) return false;
    }
    return true;
  }
  if (a.is_array()) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!near(a[i], b[i])) return false;
    }
    return true;
  }
  return a == b;
}

std::string name_of(const std::string& stage, const SettingInfo& info) {
  return (stage.empty() ? "" : stage + ".") + info.name;
}

TEST(FindSettings, EveryFieldHasAVariantAndAUniqueKey) {
  std::set<std::string> fields, keys;
  test::for_each_variant(FindSettings(),
                         [&](const std::string& stage, const SettingInfo& info, const FindSettings&,
                             const std::string&) { fields.insert(name_of(stage, info)); });
  for (const std::string& key : find_setting_keys()) {
    EXPECT_TRUE(keys.insert(key).second) << key << " is the key of two settings";
  }
  EXPECT_EQ(fields.size(), keys.size()) << "a field without another valid value is untested";
  // The flat struct this replaced held 25 settings (and two requests: progress and aligned points);
  // field_band is new.
  EXPECT_GE(keys.size(), 26u);
}

TEST(FindSettings, EveryFieldRoundTripsThroughJson) {
  const json defaults = detail::find_settings_to_json(FindSettings());
  test::for_each_variant(FindSettings(), [&](const std::string& stage, const SettingInfo& info,
                                             const FindSettings& variant, const std::string&) {
    const json written = detail::find_settings_to_json(variant);
    EXPECT_NE(written, defaults) << name_of(stage, info) << " is missing from the JSON";
    FindSettings read;
    detail::find_settings_from_json(written, "settings", read);
    EXPECT_TRUE(near(detail::find_settings_to_json(read), written)) << name_of(stage, info);
  });
}

TEST(FindSettings, EveryFieldIsSetFromItsFlagText) {
  test::for_each_variant(FindSettings(), [&](const std::string& stage, const SettingInfo& info,
                                             const FindSettings& variant, const std::string& text) {
    if (text.empty()) return;  // unsetting an optional has no flag text
    FindSettings set;
    set_find_setting(set, info.key(), text);
    EXPECT_TRUE(near(detail::find_settings_to_json(set), detail::find_settings_to_json(variant)))
        << name_of(stage, info) << " from '" << text << "'";
  });
}

TEST(FindSettings, BadTextIsRefusedNamingTheFlagAndChangesNothing) {
  const std::string defaults = detail::find_settings_to_json(FindSettings()).dump();
  for (const std::string& key : find_setting_keys()) {
    std::size_t refused = 0;
    for (const char* bad : {"abc", "nan", "1 2", "-1e300"}) {
      FindSettings s;
      try {
        set_find_setting(s, key, bad);
        continue;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      }
      ++refused;
      EXPECT_EQ(detail::find_settings_to_json(s).dump(), defaults) << key << " = '" << bad << "'";
    }
    EXPECT_GE(refused, 3u) << key << " takes values it should refuse";
  }
  FindSettings s;
  EXPECT_THROW(set_find_setting(s, "colour", "red"), Error);
  EXPECT_THROW(set_find_setting(s, "max-seeds", "-3"), Error);  // not wrapped around
  EXPECT_THROW(set_find_setting(s, "threshold", "inf"), Error);
  EXPECT_THROW(set_find_setting(s, "max-tilt", "200"), Error);  // degrees, at most 180
  set_find_setting(s, "max-tilt", "30");
  EXPECT_NEAR(s.fast.max_tilt, M_PI / 6.0, 1e-12);
  set_find_setting(s, "max-empty-violation", "0.02");  // the flag's older name
  EXPECT_EQ(s.selection.max_empty_space_violation, 0.02);
}

TEST(FindSettings, ValidationNamesTheStageAndTheFlag) {
  FindSettings s;
  s.fast.max_tilt = 4.0;
  try {
    validate(s);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fast.max_tilt (--max-tilt)"), std::string::npos)
        << e.what();
  }
  s = FindSettings();
  s.scene.coarse_leaf = 0.002;  // below the 5 mm leaf
  EXPECT_THROW(validate(s), Error);
  s = FindSettings();
  s.selection.metric = "nope";
  EXPECT_THROW(validate(s), Error);
  EXPECT_NO_THROW(validate(FindSettings()));
}

TEST(FindSettings, JsonRefusesUnknownAndMistypedFields) {
  FindSettings s;
  EXPECT_THROW(detail::find_settings_from_json(json{{"fast", {{"max_tlit", 1}}}}, "s", s), Error);
  EXPECT_THROW(detail::find_settings_from_json(json{{"colour", 1}}, "s", s), Error);
  EXPECT_THROW(detail::find_settings_from_json(json{{"fast", {{"max_candidates", -1}}}}, "s", s),
               Error);
  EXPECT_THROW(detail::find_settings_from_json(json{{"sampling", {{"seed", "1"}}}}, "s", s), Error);
  detail::find_settings_from_json(json{{"fast", {{"max_candidates", 12}}}}, "s", s);
  EXPECT_EQ(s.fast.max_candidates, 12u);
}

// A method's own settings are named as the method and change its results alone, so that a new
// method's group never enters another's cache key (walking docs/developing.md's checklist with a
// third method found the rule written for two).
TEST(FindSettings, AMethodsOwnGroupAffectsThatMethodAlone) {
  for (std::size_t m = 0; m < search_methods().size(); ++m) {
    for (const std::string& group : search_methods()) {
      EXPECT_EQ(settings_group_affects(static_cast<SearchMethod>(m), group),
                group == search_methods()[m])
          << search_methods()[m] << " and the group " << group;
    }
    for (const char* shared : {"scene", "sampling", "selection"})
      EXPECT_TRUE(settings_group_affects(static_cast<SearchMethod>(m), shared)) << shared;
    EXPECT_FALSE(settings_group_affects(static_cast<SearchMethod>(m), "execution"));
  }
}

// Issue #34, finding 2: {"threads": 2000000000} crashed the server inside oneTBB, and a field band
// of 1e308 m held it at 4.8 GB. Every count and length now has an upper bound in its description,
// which the CLI, the JSON of the page and the ROS node all read.
TEST(FindSettings, EveryCountAndLengthHasAnUpperBound) {
  FindSettings defaults;
  int numbers = 0;
  for_each_settings_group(defaults, [&](const char* group, const auto& settings) {
    std::decay_t<decltype(settings)>::describe(settings, [&](const SettingInfo& info,
                                                             const auto& value) {
      using T = std::decay_t<decltype(value)>;
      constexpr bool number =
          std::is_same_v<T, double> || std::is_same_v<T, int> || std::is_same_v<T, std::size_t> ||
          std::is_same_v<T, std::optional<double>> || std::is_same_v<T, std::optional<std::size_t>>;
      if (!number || info.name == "seed") return;  // a seed is any 64-bit number
      ++numbers;
      EXPECT_TRUE(std::isfinite(info.max)) << group << "." << info.name << " has no upper bound";
    });
  });
  EXPECT_GE(numbers, 20);
}

TEST(FindSettings, ThreadsAreBoundedByTheCoresAndTheFieldBandByTheCoarseLeaf) {
  FindSettings s;
  s.execution.threads = max_worker_threads();
  EXPECT_NO_THROW(validate(s));
  for (const int threads : {max_worker_threads() + 1, 2000000000, -1}) {
    s.execution.threads = threads;
    try {
      validate(s);
      ADD_FAILURE() << threads << " threads accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("execution.threads (--threads)"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(check_worker_threads(max_worker_threads() + 1, "test"), Error);
  EXPECT_NO_THROW(check_worker_threads(0, "test"));
  s = FindSettings();
  for (const double band : {1e308, 5.0, 0.21}) {
    s.scene.field_band = band;
    EXPECT_THROW(validate(s), Error) << band;
  }
  s.scene.field_band = 0.1;  // 10 coarse leaves of 1 cm
  EXPECT_NO_THROW(validate(s));
  s.scene.field_band = 0.11;
  try {
    validate(s);
    ADD_FAILURE() << "a band of 11 coarse leaves accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at most 10 coarse leaves"), std::string::npos)
        << e.what();
  }
  json j = {{"execution", {{"threads", 2000000000}}}};
  EXPECT_THROW(detail::find_settings_from_json(j, "s", s), Error);
}

}  // namespace
}  // namespace lmk
