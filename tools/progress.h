// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A progress bar on stderr for long runs, drawn only when stderr is a terminal so that logs and
// pipes stay clean. Safe to call from several threads.

#include <atomic>
#include <cstddef>
#include <string>

namespace lmk::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();  ///< ends the line if anything was drawn
  /// Reports `done` of `total`; redraws at most once per percent.
  void update(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool enabled_;
  std::atomic<int> last_percent_{-1};
};

}  // namespace lmk::cli
