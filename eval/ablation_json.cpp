// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/ablation_json.h"

#include "lmk/eval/internal/rows_json.h"
#include "lmk/geometry/version.h"
#include "lmk/search/internal/find_settings_json.h"

namespace lmk::detail {

using nlohmann::json;

nlohmann::json ablation_to_json(const std::vector<AblationVariant>& variants,
                                const std::string& dataset) {
  nlohmann::json list = nlohmann::json::array();
  for (const AblationVariant& v : variants) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [key, value] : v.values) values[key] = value;
    list.push_back({{"values", values},
                    {"settings", find_settings_to_json(v.evaluation.settings.find)},
                    {"seconds", v.evaluation.seconds},
                    {"rows", rows_to_json(v.rows)}});
  }
  return {{"format", "lmk-ablation"},
          {"version", 1},
          {"lmk_version", kVersion},
          {"dataset", dataset},
          {"dataset_fingerprint", variants.empty() ? "" : variants.front().evaluation.fingerprint},
          {"variants", list}};
}

}  // namespace lmk::detail
