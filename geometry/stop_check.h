// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How a caller stops a long computation (issue #47: a cancelled job of lmk serve that was indexing
// a 5-million-point scene stayed running for 12.9 s). The computation calls the check between
// pieces of its work, each well under 200 ms on the largest scene lmk reads; the check throws (the
// caller's own exception) to stop it, from inside parallel loops too (TBB cancels the loop and
// rethrows in the caller). Empty: nothing ever stops it.
#include <cstddef>
#include <functional>

namespace lmk {

using StopCheck = std::function<void()>;

/// Items of a point loop between two checks: a few milliseconds of the slowest loop's work.
inline constexpr std::size_t kItemsPerStopCheck = 16384;

/// Calls `stop` every kItemsPerStopCheck-th item `i` of a loop.
inline void check_every(const StopCheck& stop, std::size_t i) {
  if (stop && i % kItemsPerStopCheck == 0) stop();
}

}  // namespace lmk
