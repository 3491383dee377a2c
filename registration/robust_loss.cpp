// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/registration/robust_loss.h"

#include <cmath>

#include "lmk/geometry/error.h"

namespace lmk {

double RobustLoss::weight(double residual) const {
  const double r = std::abs(residual);
  switch (kernel) {
    case RobustKernel::none:
      return 1.0;
    case RobustKernel::huber:
      return r <= scale ? 1.0 : scale / r;
    case RobustKernel::cauchy:
      return 1.0 / (1.0 + (r / scale) * (r / scale));
    case RobustKernel::tukey: {
      if (r >= scale) return 0.0;
      const double u = 1.0 - (r / scale) * (r / scale);
      return u * u;
    }
  }
  return 1.0;
}

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
