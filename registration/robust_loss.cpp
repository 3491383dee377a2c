// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/robust_loss.h"

#include "lmk/geometry/error.h"

namespace lmk {

std::string to_string(RobustKernel kernel) {
  switch (kernel) {
    case RobustKernel::none:
      return "none";
    case RobustKernel::huber:
      return "huber";
    case RobustKernel::cauchy:
      return "cauchy";
    case RobustKernel::tukey:
      return "tukey";
  }
  return "none";
}

RobustKernel robust_kernel_from_string(const std::string& name) {
  for (RobustKernel k :
       {RobustKernel::none, RobustKernel::huber, RobustKernel::cauchy, RobustKernel::tukey}) {
    if (to_string(k) == name) return k;
  }
  throw Error("unknown robust loss '" + name + "' (known: none, huber, cauchy, tukey)");
}

}  // namespace lmk
