// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Robust kernels shared by ICP (as iteratively reweighted least squares) and the Ceres refinement
// (as Ceres loss functions), so that one setting means the same thing in both.

#include <cmath>
#include <string>
#include <vector>

namespace lmk {

enum class RobustKernel { none, huber, cauchy, tukey };

struct RobustLoss {
  RobustKernel kernel = RobustKernel::none;
  double scale = 0.01;  ///< residual size, m, at which the kernel starts to discount a residual

  /// The IRLS weight of a residual r: 1 for `none`; Huber min(1, s/|r|); Cauchy 1/(1+(r/s)^2);
  /// Tukey (1-(r/s)^2)^2 inside s and 0 beyond.
  /// Inline: ICP asks it once per correspondence.
  double weight(double residual) const {
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
};

/// "none", "huber", "cauchy", "tukey".
std::string to_string(RobustKernel kernel);
/// The kernel called `name`; throws lmk::Error listing the known names otherwise.
RobustKernel robust_kernel_from_string(const std::string& name);

}  // namespace lmk
