// SPDX-License-Identifier: BSD-3-Clause
// lmk metrics [NAME...] [--json]: the error metrics a search can use (built in, and those of the
// plugins $LMK_METRIC_PLUGINS names), each with what it says of itself (ErrorMetric).

#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/search/internal/error_metric_json.h"
#include "lmk/search/metrics/error_metrics.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct MetricsOptions {
  std::vector<std::string> names;  ///< empty: every registered metric
  bool json = false;
};

// One line per metric: its threshold and prune bound as it shows errors, then what it is.
void print_metric(const ErrorMetric& m) {
  const std::string prune =
      m.coarse_score ? "prunes at " + format_error(m.prune_bound(), m) : "no coarse score";
  std::printf("%-12s threshold %-11s %-22s %s\n", m.name.c_str(),
              format_error(m.default_threshold, m).c_str(), prune.c_str(), m.description.c_str());
}

int run_metrics(const MetricsOptions& o) {
  std::vector<const ErrorMetric*> shown;
  for (const std::string& name : o.names) shown.push_back(&find_error_metric(name));
  if (o.names.empty()) {
    for (const ErrorMetric& m : error_metrics()) shown.push_back(&m);
  }
  if (o.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const ErrorMetric* m : shown) out.push_back(detail::error_metric_to_json(*m));
    std::cout << out.dump(2) << "\n";
    return kOk;
  }
  for (const ErrorMetric* m : shown) print_metric(*m);
  return kOk;
}

}  // namespace

Subcommand add_metrics(CLI::App& app) {
  auto o = std::make_shared<MetricsOptions>();
  CLI::App* sub = app.add_subcommand(
      "metrics",
      "List the error metrics a search can use (--metric), built in and from the plugins "
      "$LMK_METRIC_PLUGINS names, with their thresholds and the fast search's prune bounds");
  sub->add_option("names", o->names, "Only these metrics (default: every one)");
  sub->add_flag("--json", o->json, "Write JSON instead of a table");
  return {sub, [o] { return run_metrics(*o); }};
}

}  // namespace lmk::cli
