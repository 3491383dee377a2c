// SPDX-License-Identifier: BSD-3-Clause
// Issue #47: every number a user can set has a range. Generated from the one description each
// settings struct has (geometry/settings_schema.h), so that a new numeric setting without bounds
// fails here before any user can give it 1e308.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "lmk/landmark/box_guess.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/find_settings.h"

namespace lmk {
namespace {

template <class T>
struct IsNumber
    : std::integral_constant<bool, std::is_arithmetic<T>::value && !std::is_same<T, bool>::value> {
};
template <class T>
struct IsNumber<std::optional<T>> : IsNumber<T> {};

/// The numeric fields of a described struct whose range is not finite on both sides.
struct UnboundedNumbers {
  std::string group;
  std::vector<std::string> found;
  std::size_t numbers = 0;

  template <class T>
  void operator()(const SettingInfo& info, const T&) {
    if constexpr (IsNumber<T>::value) {
      ++numbers;
      if (!std::isfinite(info.min) || !std::isfinite(info.max)) {
        found.push_back(group + "." + info.name);
      }
    }
  }
};

template <class Settings>
std::size_t expect_bounded(const std::string& group, const Settings& settings) {
  UnboundedNumbers visit{group, {}, 0};
  Settings::describe(settings, visit);
  EXPECT_TRUE(visit.found.empty()) << "numbers without a finite range: " << [&] {
    std::string names;
    for (const std::string& n : visit.found) names += n + " ";
    return names;
  }();
  return visit.numbers;
}

TEST(SettingsRanges, EveryNumberOfEveryDescriptionHasAFiniteRange) {
  std::size_t numbers = 0;
  const FindSettings find;
  for_each_settings_group(find, [&](const char* group, const auto& settings) {
    numbers += expect_bounded(group, settings);
  });
  numbers += expect_bounded("capture", CaptureSettings());
  numbers += expect_bounded("guess", BoxGuessSettings());
  EXPECT_GT(numbers, 30u);  // the visitor saw the numbers at all
}

TEST(SettingsRanges, ADistanceBandIsBoundedByTheLeafBeforeAnythingIsBuilt) {
  CaptureSettings s;
  s.leaf_size = 0.001;
  s.distance_band = 0.05;  // 50 leaves of a millimetre
  try {
    check_capture_settings(s, "capture");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("must be at most 40 leaves"), std::string::npos)
        << e.what();
  }
  s.distance_band = 1e308;
  EXPECT_THROW(check_capture_settings(s, "capture"), Error);
  s.distance_band = 0.02;  // the default, 20 leaves of a millimetre
  EXPECT_NO_THROW(check_capture_settings(s, "capture"));
}

}  // namespace
}  // namespace lmk
