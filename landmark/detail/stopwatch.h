// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Wall-clock timing of search stages, for the statistics every search reports. Internal.

#include <chrono>

namespace lmk::detail {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace lmk::detail
