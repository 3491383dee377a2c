// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One demo-task scenario's result as JSON, for the report and for the demo-task cache. Internal.

#include <nlohmann/json.hpp>

#include "lmk/demos/demo_tasks.h"

namespace lmk::detail {

nlohmann::json scenario_to_json(const DemoScenarioResult& result);
/// Reads what scenario_to_json wrote; throws nlohmann::json::exception for anything else.
DemoScenarioResult scenario_from_json(const nlohmann::json& j);

}  // namespace lmk::detail
