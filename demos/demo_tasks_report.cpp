// SPDX-License-Identifier: BSD-3-Clause
// The demo tasks' report: its totals, its table as the paper prints its Tables IV-IX, and its
// JSON.

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "lmk/demos/demo_tasks.h"
#include "lmk/demos/detail/demo_tasks_json.h"
#include "lmk/eval/text_table.h"
#include "lmk/geometry/statistics.h"

namespace lmk {

std::size_t DemoTasksReport::succeeded() const {
  return static_cast<std::size_t>(std::count_if(
      scenarios.begin(), scenarios.end(), [](const DemoScenarioResult& r) { return r.success; }));
}

std::size_t DemoTasksReport::wrong_motions() const {
  return static_cast<std::size_t>(
      std::count_if(scenarios.begin(), scenarios.end(),
                    [](const DemoScenarioResult& r) { return r.wrong_motion; }));
}

std::size_t DemoTasksReport::refusals() const {
  return static_cast<std::size_t>(std::count_if(
      scenarios.begin(), scenarios.end(), [](const DemoScenarioResult& r) { return r.refused; }));
}

std::size_t DemoTasksReport::contacts() const {
  std::size_t n = 0;
  for (const DemoScenarioResult& r : scenarios) n += r.contacts;
  return n;
}

std::vector<double> DemoTasksReport::seconds_planning_around() const {
  std::vector<double> all;
  for (const DemoScenarioResult& r : scenarios)
    all.insert(all.end(), r.seconds_planning_around.begin(), r.seconds_planning_around.end());
  return all;
}

std::string demo_tasks_table(const DemoTasksReport& report) {
  TextTable table;
  table.header = {"task",  "scenario", "should act", "success", "outcome",
                  "looks", "re-plans", "contacts",   "reason"};
  for (const DemoScenarioResult& r : report.scenarios) {
    const char* outcome = r.wrong_motion ? "WRONG MOTION"
                          : r.refused    ? "refused"
                          : r.stopped    ? "stopped"
                                         : "acted";
    table.rows.push_back({std::to_string(r.task) + " " + r.task_title, r.name,
                          r.should_act ? "yes" : "no", r.success ? "yes" : "NO", outcome,
                          std::to_string(r.looks), std::to_string(r.replans),
                          std::to_string(r.contacts), r.reason});
  }
  // The paper's six tasks apart, the ones its 26 of 30 counts.
  std::size_t paper_total = 0, paper_succeeded = 0;
  for (const DemoScenarioResult& r : report.scenarios) {
    if (r.task > 6) continue;
    ++paper_total;
    paper_succeeded += r.success;
  }
  char paper[80] = "";
  if (paper_total > 0) {
    std::snprintf(paper, sizeof(paper), " (tasks 1-6: %zu of %zu; the paper: 26 of 30)",
                  paper_succeeded, paper_total);
  }
  char total[240];
  std::snprintf(total, sizeof(total),
                "succeeded %zu of %zu scenarios%s, %zu wrong motion(s), %zu refusal(s), %zu "
                "contact(s), in %.1f s\n",
                report.succeeded(), report.total(), paper, report.wrong_motions(),
                report.refusals(), report.contacts(), report.seconds);
  std::string planning;
  if (const std::vector<double> around = report.seconds_planning_around(); !around.empty()) {
    char line[160];
    std::snprintf(line, sizeof(line),
                  "planned around an obstacle: %zu motion(s), median %.2f s, 95th percentile "
                  "%.2f s\n",
                  around.size(), *median(around), percentile(around, 0.95));
    planning = line;
  }
  return table.plain() + total + planning;
}

namespace detail {

nlohmann::json scenario_to_json(const DemoScenarioResult& r) {
  return {{"task", r.task},
          {"task_title", r.task_title},
          {"name", r.name},
          {"should_act", r.should_act},
          {"success", r.success},
          {"wrong_motion", r.wrong_motion},
          {"refused", r.refused},
          {"stopped", r.stopped},
          {"reason", r.reason},
          {"steps_executed", r.steps_executed},
          {"max_position_error_m", r.max_position_error},
          {"max_rotation_error_rad", r.max_rotation_error},
          {"seconds", r.seconds},
          {"looks", r.looks},
          {"replans", r.replans},
          {"contacts", r.contacts},
          {"first_contact", r.first_contact},
          {"seconds_planning_around", r.seconds_planning_around}};
}

DemoScenarioResult scenario_from_json(const nlohmann::json& j) {
  DemoScenarioResult r;
  r.task = j.at("task").get<int>();
  r.task_title = j.at("task_title").get<std::string>();
  r.name = j.at("name").get<std::string>();
  r.should_act = j.at("should_act").get<bool>();
  r.success = j.at("success").get<bool>();
  r.wrong_motion = j.at("wrong_motion").get<bool>();
  r.refused = j.at("refused").get<bool>();
  r.stopped = j.value("stopped", false);
  r.reason = j.at("reason").get<std::string>();
  r.steps_executed = j.at("steps_executed").get<std::size_t>();
  r.max_position_error = j.at("max_position_error_m").get<double>();
  r.max_rotation_error = j.at("max_rotation_error_rad").get<double>();
  r.seconds = j.at("seconds").get<double>();
  r.looks = j.value("looks", std::size_t{0});
  r.replans = j.value("replans", std::size_t{0});
  r.contacts = j.value("contacts", std::size_t{0});
  r.first_contact = j.value("first_contact", std::string());
  r.seconds_planning_around = j.value("seconds_planning_around", std::vector<double>{});
  return r;
}

}  // namespace detail

std::string demo_tasks_json(const DemoTasksReport& report) {
  nlohmann::json scenarios = nlohmann::json::array();
  for (const DemoScenarioResult& r : report.scenarios)
    scenarios.push_back(detail::scenario_to_json(r));
  return nlohmann::json{{"scenarios", scenarios},
                        {"succeeded", report.succeeded()},
                        {"wrong_motions", report.wrong_motions()},
                        {"refusals", report.refusals()},
                        {"contacts", report.contacts()},
                        {"total", report.total()},
                        {"seconds", report.seconds}}
             .dump(2) +
         "\n";
}

}  // namespace lmk
