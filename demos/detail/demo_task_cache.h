// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The demo tasks' cache (DemoTasksSettings::cache_dir): a finished task's scenario results, kept
// so that an interrupted `lmk pbd demo-tasks --cache DIR` resumes with the tasks it did not finish.

#include <optional>
#include <vector>

#include "lmk/demos/demo_tasks.h"

namespace lmk {

/// The results of `task` kept by an earlier run with the same settings and lmk version, if any.
/// A damaged or foreign file counts as none.
std::optional<std::vector<DemoScenarioResult>> read_cached_demo_task(
    const DemoTasksSettings& settings, int task);

/// Keeps the results of `task` (atomically; lmk::Error when the cache cannot be written).
void write_cached_demo_task(const DemoTasksSettings& settings, int task,
                            const std::vector<DemoScenarioResult>& results);

}  // namespace lmk
