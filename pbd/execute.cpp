// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/execute.h"

#include <cmath>
#include <cstdio>

#include "lmk/pbd/internal/execute_step.h"

namespace lmk {
namespace {

// Whether the robot's arm joints are where the plan starts; the first one that is not, otherwise.
std::string check_start(const Plan& plan, const RobotInterface& robot, double tolerance) {
  JointState state;
  const CallResult read = robot.read_joint_state(state);
  if (!read.ok()) return "cannot read the joint state: " + read.message;
  std::map<std::string, double> now;
  for (std::size_t i = 0; i < state.names.size() && i < state.positions.size(); ++i) {
    now[state.names[i]] = state.positions[i];
  }
  for (const auto& [name, planned] : plan.start) {
    const auto it = now.find(name);
    if (it == now.end()) return "the robot reports no joint '" + name + "'";
    // Continuous joints may report the same angle a turn apart.
    if (std::abs(std::remainder(it->second - planned, 2.0 * M_PI)) > tolerance) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    "joint '%s' is at %.4f, the plan starts from %.4f: the robot moved since "
                    "planning; plan again",
                    name.c_str(), it->second, planned);
      return text;
    }
  }
  return "";
}

}  // namespace

bool send_motions(const PlannedStep& step, RobotInterface& robot, ExecutionReport& report) {
  const std::string where = "step " + std::to_string(step.index) + ": ";
  for (const PlannedArm& a : step.arms) {
    const CallResult r = robot.send_trajectory(arm_group(a.arm), a.trajectory);
    if (!r.ok()) {
      report.error = where + arm_group(a.arm) + ": " + r.message;
      return false;
    }
    char text[160];
    const Eigen::Vector3d p = a.T_base_ee.translation();
    std::snprintf(text, sizeof(text), "%s%s to (%.3f, %.3f, %.3f) in %.1f s", where.c_str(),
                  arm_group(a.arm).c_str(), p.x(), p.y(), p.z(), step.duration);
    report.log.push_back(text);
  }
  return true;
}

bool send_gripper_commands(const PlannedStep& step, RobotInterface& robot,
                           const ExecuteSettings& settings, ExecutionReport& report) {
  const std::string where = "step " + std::to_string(step.index) + ": ";
  for (const PlannedArm& a : step.arms) {
    GripperCommand command;
    command.position =
        a.gripper == GripperAction::kOpen ? settings.gripper_open : settings.gripper_closed;
    const CallResult r = robot.command_gripper(arm_gripper(a.arm), command);
    if (!r.ok()) {
      report.error = where + arm_gripper(a.arm) + " gripper: " + r.message;
      return false;
    }
    report.log.push_back(where + arm_gripper(a.arm) + " gripper " + gripper_action_name(a.gripper));
  }
  return true;
}

bool may_start(const Plan& plan, const RobotInterface& robot, const ExecuteSettings& settings,
               ExecutionReport& report) {
  report.steps_total = plan.steps.size();
  if (plan.refusal) {
    report.error = "refused: " + describe(*plan.refusal);
    return false;
  }
  report.error = check_start(plan, robot, settings.start_tolerance);
  if (!report.error.empty()) return false;
  report.started = true;
  return true;
}

ExecutionReport execute(const Plan& plan, RobotInterface& robot, const ExecuteSettings& settings) {
  ExecutionReport report;
  if (!may_start(plan, robot, settings, report)) return report;
  for (const PlannedStep& step : plan.steps) {
    if (!send_motions(step, robot, report) ||
        !send_gripper_commands(step, robot, settings, report)) {
      return report;
    }
    ++report.steps_completed;
    if (settings.progress) settings.progress(report.steps_completed, report.steps_total);
  }
  report.completed = true;
  return report;
}

}  // namespace lmk
