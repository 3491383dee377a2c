// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Robust kernels shared by ICP (as iteratively reweighted least squares) and the Ceres refinement
// (as Ceres loss functions), so that one setting means the same thing in both.

#include <string>
#include <vector>

namespace lmk {

enum class RobustKernel { none, huber, cauchy, tukey };

struct RobustLoss {
  RobustKernel kernel = RobustKernel::none;
  double scale = 0.01;  ///< residual size, m, at which the kernel starts to discount a residual

  /// The IRLS weight of a residual r: 1 for `none`; Huber min(1, s/|r|); Cauchy 1/(1+(r/s)^2);
  /// Tukey (1-(r/s)^2)^2 inside s and 0 beyond.
  double weight(double residual) const;
};

/// "none", "huber", "cauchy", "tukey".
std::string to_string(RobustKernel kernel);
/// The kernel called `name`; throws lmk::Error listing the known names otherwise.
RobustKernel robust_kernel_from_string(const std::string& name);

}  // namespace lmk
