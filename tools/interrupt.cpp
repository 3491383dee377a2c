// SPDX-License-Identifier: BSD-3-Clause
#include "tools/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace lmk::cli {

namespace {

std::atomic<bool> sigint_received{false};

extern "C" void on_sigint(int) {
  if (sigint_received.exchange(true)) {  // the second one: quit at once
    std::signal(SIGINT, SIG_DFL);
    std::raise(SIGINT);
    return;
  }
  // Only async-signal-safe calls here: write(2), not stdio.
  static const char message[] =
      "\nlmk: stopping after the searches under way (Ctrl-C again to quit at once)\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, message, sizeof(message) - 1);
}

}  // namespace

StopOnSigint::StopOnSigint() {
  sigint_received = false;
  std::signal(SIGINT, on_sigint);
}

StopOnSigint::~StopOnSigint() { std::signal(SIGINT, SIG_DFL); }

bool StopOnSigint::requested() { return sigint_received.load(); }

}  // namespace lmk::cli
