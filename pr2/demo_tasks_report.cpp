// The demo tasks' table, as the paper prints its Tables IV-IX, and their JSON.

#include <cstdio>
#include <nlohmann/json.hpp>

#include "eval/text_table.h"
#include "pr2/demo_tasks.h"

namespace lmk {

std::string demo_tasks_table(const DemoTasksReport& report) {
  TextTable table;
  table.header = {"task", "scenario", "should act", "success", "reason"};
  for (const DemoScenarioResult& r : report.scenarios) {
    table.rows.push_back({std::to_string(r.task) + " " + r.task_title, r.name,
                          r.should_act ? "yes" : "no", r.success ? "yes" : "NO", r.reason});
  }
  char total[160];
  std::snprintf(total, sizeof(total),
                "succeeded %zu of %zu scenarios (the paper: 26 of 30) in %.1f s\n",
                report.succeeded(), report.total(), report.seconds);
  return table.plain() + total;
}

std::string demo_tasks_json(const DemoTasksReport& report) {
  nlohmann::json scenarios = nlohmann::json::array();
  for (const DemoScenarioResult& r : report.scenarios) {
    scenarios.push_back({{"task", r.task},
                         {"task_title", r.task_title},
                         {"name", r.name},
                         {"should_act", r.should_act},
                         {"success", r.success},
                         {"reason", r.reason},
                         {"steps_executed", r.steps_executed},
                         {"max_position_error_m", r.max_position_error},
                         {"max_rotation_error_rad", r.max_rotation_error},
                         {"seconds", r.seconds}});
  }
  return nlohmann::json{{"scenarios", scenarios},
                        {"succeeded", report.succeeded()},
                        {"total", report.total()},
                        {"seconds", report.seconds}}
             .dump(2) +
         "\n";
}

}  // namespace lmk
