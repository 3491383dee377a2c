// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How a process that searches frame after frame asks the C library to keep the memory a search
// frees for the next one. glibc maps a buffer above its mmap threshold (128 KiB at first) straight
// from the kernel and unmaps it when freed, and hands the top of its heap back above a trim
// threshold; both move only as mapped buffers are freed. A search's buffers of a few megabytes
// were then mapped, faulted in and zeroed again by the kernel, search after search, or not,
// depending on what the process had freed before: `paper` searched 2% slower per search than with
// fixed thresholds, and a buffer freed elsewhere once made its voting 60% slower (issue #63).

namespace lmk {

/// Buffers below this are taken from the heap and reused: a Kinect frame's largest (a 640 x 480
/// image of 3-D points and colours, about 5 MB) and more.
constexpr long kHeapBufferBytes = 32L << 20;
/// Freed memory at the top of the heap is kept up to this, and returned beyond it.
constexpr long kHeapKeepBytes = 256L << 20;

/// Fixes the C library's thresholds at kHeapBufferBytes and kHeapKeepBytes for the whole process.
/// For programs, not libraries: lmk's tool and ROS node call it first thing. A long-running
/// process that must give memory back between jobs still can (malloc_trim, as `lmk serve` does).
/// Does nothing where the C library is not glibc.
void keep_freed_memory_for_reuse();

}  // namespace lmk
