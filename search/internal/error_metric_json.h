// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An error metric as `lmk metrics --json` and Python's lmk.error_metrics() give it: what it says
// of itself (ErrorMetric), in its own unit. Internal.

#include <nlohmann/json.hpp>

#include "lmk/search/metrics/error_metrics.h"

namespace lmk::detail {

inline nlohmann::json error_metric_to_json(const ErrorMetric& m) {
  return {{"name", m.name},
          {"description", m.description},
          {"default_threshold", m.default_threshold},
          {"error_unit", m.display.json_unit},
          {"shown_unit", m.display.label},
          {"shown_scale", m.display.scale},
          {"coarse_score", static_cast<bool>(m.coarse_score)},
          // Without a coarse score nothing is pruned.
          {"prune_bound", m.coarse_score ? nlohmann::json(m.prune_bound()) : nlohmann::json()},
          {"noise_normalised", m.noise_normalised},
          {"needs_empty_distances", m.needs_empty_distances},
          {"hides_occluded", m.hides_occluded}};
}

}  // namespace lmk::detail
