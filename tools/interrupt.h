// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ctrl-C for the long runs (eval, ablate, pbd demo-tasks): the first SIGINT asks the run to stop
// after the work under way, which is then cached, so that the same command resumes; a second
// SIGINT ends the process at once, as without a handler.

namespace lmk::cli {

/// Installs the handler for its lifetime (the default handling comes back after it).
class StopOnSigint {
 public:
  StopOnSigint();
  ~StopOnSigint();
  StopOnSigint(const StopOnSigint&) = delete;
  StopOnSigint& operator=(const StopOnSigint&) = delete;

  /// Whether a SIGINT has arrived since the handler was installed. Safe from any thread.
  static bool requested();
};

}  // namespace lmk::cli
