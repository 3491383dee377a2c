// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/detail/vdb_support.h"

#include <mutex>

namespace lmk::detail {

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

}  // namespace lmk::detail
