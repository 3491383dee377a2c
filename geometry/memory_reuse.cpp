// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/memory_reuse.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace lmk {

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
  // Setting either threshold also stops glibc moving them as buffers are freed.
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(kHeapBufferBytes));
  mallopt(M_TRIM_THRESHOLD, static_cast<int>(kHeapKeepBytes));
#endif
}

}  // namespace lmk
