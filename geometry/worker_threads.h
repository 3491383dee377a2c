// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one bound on worker threads that every setting of them shares (FindSettings' `threads`, lmk
// eval's, lmk pbd's and lmk bench's --threads, the page's and the ROS node's settings): oneTBB
// crashed inside its arena on 2,000,000,000 threads and threw std::bad_alloc on 100,000,000
// (issue #34, finding 2), and past a few per core more threads only wait for one.
#include <functional>
#include <string>

namespace lmk {

/// Threads per core any setting may ask for: room for waiting on I/O, not for oversubscription.
constexpr int kMaxThreadsPerCore = 4;

/// kMaxThreadsPerCore times this machine's cores (at least kMaxThreadsPerCore).
int max_worker_threads();

/// Throws lmk::Error "WHAT: N threads: must be in [0, MAX] (0 uses every core; at most 4 per core
/// of this machine)" for a count outside [0, max_worker_threads()].
void check_worker_threads(int threads, const std::string& what);

/// Runs `work` on at most `threads` threads (0: every core), the calling thread among them: every
/// parallel loop inside it shares that bound, with no process-wide thread setting.
void with_worker_threads(int threads, const std::function<void()>& work);

}  // namespace lmk
