// SPDX-License-Identifier: BSD-3-Clause
#include "tools/progress.h"

#include <unistd.h>

#include <cstdio>

namespace lmk::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), enabled_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && last_percent_ >= 0) std::fputc('\n', stderr);
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const int percent = static_cast<int>(100 * done / total);
  int last = last_percent_.load();
  // Only the thread that advances the percentage draws, so lines never interleave.
  while (percent > last) {
    if (last_percent_.compare_exchange_weak(last, percent)) {
      constexpr int kWidth = 30;
      const int filled = percent * kWidth / 100;
      std::fprintf(stderr, "\r%s [%-*s] %3d%% (%zu/%zu)", label_.c_str(), kWidth,
                   std::string(static_cast<std::size_t>(filled), '#').c_str(), percent, done,
                   total);
      std::fflush(stderr);
      return;
    }
  }
}

}  // namespace lmk::cli
