// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/find_result.h"

#include <string>

namespace lmk {

// RejectionCounts holds one count per reason: a reason added after the last must raise it.
static_assert(static_cast<std::size_t>(RejectionReason::suppressed_by_a_better_match) + 1 ==
                  kRejectionReasons,
              "kRejectionReasons must count every RejectionReason");

const char* to_string(RejectionReason reason) {
  switch (reason) {
    case RejectionReason::error_above_threshold:
      return "error above threshold";
    case RejectionReason::colour_differs:
      return "colour differs";
    case RejectionReason::coverage_too_low:
      return "coverage too low";
    case RejectionReason::empty_space_occupied:
      return "empty space occupied";
    case RejectionReason::inside_a_better_match:
      return "inside a better match";
    case RejectionReason::too_little_shown:
      return "shows too little to fix its pose";
    case RejectionReason::confidence_too_low:
      return "confidence too low";
    case RejectionReason::suppressed_by_a_better_match:
      return "suppressed by a better match";
  }
  return "?";
}

std::string describe_rejections(const SearchStats& s) {
  if (s.after_nms == 0) {
    return "no candidate pose: nothing in the scene has the landmark's shape";
  }
  std::string out;
  for (const RejectionReason why :
       {RejectionReason::error_above_threshold, RejectionReason::colour_differs,
        RejectionReason::coverage_too_low, RejectionReason::empty_space_occupied,
        RejectionReason::inside_a_better_match, RejectionReason::too_little_shown,
        RejectionReason::confidence_too_low}) {
    const std::size_t n = s.rejected[why];
    if (n == 0) continue;
    out += (out.empty() ? "rejected: " : ", ") + std::to_string(n) + " " + to_string(why);
  }
  return out;
}

}  // namespace lmk
