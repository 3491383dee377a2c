// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of a search's result, which `lmk find --json` prints and `lmk serve` answers with:
// {"matches": [...], "stats": {...}}, each match its box pose, error, terms and confidence
// (internal/confidence_json.h; a rejected candidate only when it was assessed); with rejections,
// also "rejected": the candidates turned down after non-max suppression, each with its reason.
// Header-only; internal/: shared within lmk (the CLI, serve, ROS, Python), not installed.

#include <cmath>
#include <nlohmann/json.hpp>

#include "lmk/json/pose_json.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/internal/confidence_json.h"
#include "lmk/search/internal/terms_json.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk::detail {

inline nlohmann::json match_to_json(const Match& m) {
  nlohmann::json match = pose_to_json(m.box.pose);
  match["error"] = m.error;
  match["terms"] = terms_to_json(m.terms);
  match["seed_index"] = m.seed_index;
  match["icp_iterations"] = m.icp_iterations;
  match["votes"] = m.votes;
  // Only what the search assessed (every match, and candidates turned down for their confidence):
  // a candidate turned down earlier has no evidence to show.
  if (!std::isnan(m.confidence.error_sigma)) match["confidence"] = confidence_to_json(m.confidence);
  return match;
}

inline nlohmann::json search_stats_to_json(const SearchStats& s) {
  return {{"seconds", s.seconds_total},
          {"seconds_preprocess", s.seconds_preprocess},
          {"seconds_search", s.seconds_search},
          {"seconds_select", s.seconds_select},
          {"seconds_vote", s.fast.seconds_vote},
          {"seconds_coarse", s.fast.seconds_coarse},
          {"seconds_fine", s.fast.seconds_fine},
          {"seeds", s.seeds},
          {"icp_iterations", s.icp_iterations},
          {"scene_points", s.scene_points},
          {"scene_points_used", s.scene_points_used},
          {"after_nms", s.after_nms},
          {"poses", s.fast.poses},
          {"clusters", s.fast.clusters},
          {"refined", s.fast.refined},
          {"rejected_error", s.rejected[RejectionReason::error_above_threshold]},
          {"rejected_coverage", s.rejected[RejectionReason::coverage_too_low]},
          {"rejected_empty_space", s.rejected[RejectionReason::empty_space_occupied]},
          {"rejected_overlap", s.rejected[RejectionReason::inside_a_better_match]},
          {"rejected_undetermined", s.rejected[RejectionReason::too_little_shown]},
          {"rejected_colour", s.rejected[RejectionReason::colour_differs]},
          {"rejected_confidence", s.rejected[RejectionReason::confidence_too_low]},
          {"threshold", s.threshold},
          {"method", setting_name(s.method)},
          {"metric", s.metric},
          {"rejections", describe_rejections(s)}};
}

/// The matches and statistics; with `with_rejected`, also every rejected candidate and its reason.
inline nlohmann::json find_result_to_json(const FindResult& r, bool with_rejected = false) {
  nlohmann::json matches = nlohmann::json::array();
  for (const Match& m : r.matches) matches.push_back(match_to_json(m));
  nlohmann::json j = {{"matches", matches}, {"stats", search_stats_to_json(r.stats)}};
  // The unit of every error: the metric's own (ErrorDisplay::json_unit), "m" or "sd".
  if (!r.stats.metric.empty()) {
    j["error_unit"] = find_error_metric(r.stats.metric).display.json_unit;
  }
  if (with_rejected) {
    nlohmann::json rejected = nlohmann::json::array();
    for (const Rejection& x : r.rejected) {
      nlohmann::json candidate = match_to_json(x.candidate);
      candidate["reason"] = to_string(x.reason);
      rejected.push_back(candidate);
    }
    j["rejected"] = rejected;
  }
  return j;
}

}  // namespace lmk::detail
