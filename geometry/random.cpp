// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/random.h"

#include <cmath>

namespace lmk {

double SplitMix64::normal() {
  // 1 - u keeps the logarithm's argument in (0, 1].
  const double u1 = 1.0 - uniform01();
  const double u2 = uniform01();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

}  // namespace lmk
