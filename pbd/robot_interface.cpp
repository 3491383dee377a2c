// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/robot_interface.h"

namespace lmk {

const char* lifecycle_state_name(LifecycleState state) {
  switch (state) {
    case LifecycleState::kUnconfigured:
      return "unconfigured";
    case LifecycleState::kInactive:
      return "inactive";
    case LifecycleState::kActive:
      return "active";
  }
  return "unknown";
}

CallResult lifecycle_error(const std::string& method, LifecycleState state) {
  const char* remedy = state == LifecycleState::kUnconfigured ? "configure it first"
                       : state == LifecycleState::kInactive   ? "activate it first"
                                                              : "deactivate it first";
  return CallResult::error(method + ": the robot is " + lifecycle_state_name(state) + "; " +
                           remedy);
}

}  // namespace lmk
