// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one way lmk times anything: a search's stages, a plan's searches, an evaluation, a job of
// lmk serve. Wall-clock seconds on the steady clock, which never goes back when the system clock
// is set.

#include <chrono>

namespace lmk {

/// Seconds since it was made (or restarted).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}

  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace lmk
