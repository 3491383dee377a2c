// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/worker_threads.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <thread>

#include "lmk/geometry/error.h"

namespace lmk {

int max_worker_threads() {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return kMaxThreadsPerCore * cores;
}

void check_worker_threads(int threads, const std::string& what) {
  if (threads < 0 || threads > max_worker_threads()) {
    throw Error(what + ": " + std::to_string(threads) + " threads: must be in [0, " +
                std::to_string(max_worker_threads()) + "] (0 uses every core; at most " +
                std::to_string(kMaxThreadsPerCore) + " per core of this machine)");
  }
}

void with_worker_threads(int threads, const std::function<void()>& work) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute(work);
}

}  // namespace lmk
