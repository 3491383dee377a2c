// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/motion_check.h"

#include <cmath>
#include <cstdio>

namespace lmk {

std::string format_point(const Eigen::Vector3d& p) {
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

std::string describe(const MotionContact& c) {
  char text[320];
  const bool into = c.distance < 0.0;
  std::snprintf(text, sizeof(text),
                "link %s would %s %.1f cm %s %s near (%.2f, %.2f, %.2f) m in base_link, %.0f%% of "
                "the way",
                c.link.c_str(), into ? "pass" : "come within", 100.0 * std::abs(c.distance),
                into ? "into" : "of", c.obstacle.c_str(), c.where.x(), c.where.y(), c.where.z(),
                100.0 * c.at);
  return text;
}

}  // namespace lmk
