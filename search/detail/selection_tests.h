// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Step 6's tests beside the error threshold, written once: selection turns a candidate down by
// them (find_landmark.cpp), and a match's confidence counts as a rival only a candidate that
// passes them (competitor.cpp). Internal.

#include <cmath>

#include "lmk/search/find_settings.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk::detail {

/// Fewer of the landmark's points supported than selection.min_coverage (only for metrics that
/// measure coverage).
inline bool coverage_too_low(const ErrorTerms& t, const SelectionSettings& s) {
  return t.support && t.support->coverage < s.min_coverage;
}

/// More of the landmark's observed-empty voxels occupied than selection.max_empty_space_violation
/// allows (only for metrics that test empty space).
inline bool empty_space_occupied(const ErrorTerms& t, const SelectionSettings& s) {
  return t.empty_space && t.empty_space->probes > 0 &&
         static_cast<double>(t.empty_space->violations) >
             s.max_empty_space_violation * static_cast<double>(t.empty_space->probes);
}

}  // namespace lmk::detail
