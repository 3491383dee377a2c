// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/evaluation_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/geometry/statistics.h"

namespace lmk {

std::vector<std::string> evaluation_settings(const Evaluation& evaluation) {
  std::vector<std::string> settings;
  for (const PairResult& p : evaluation.pairs) {
    if (std::find(settings.begin(), settings.end(), p.setting) == settings.end())
      settings.push_back(p.setting);
  }
  settings.push_back("all");
  return settings;
}

EvaluationRow evaluation_row(const Evaluation& evaluation, const std::string& setting,
                             int assumption, double threshold) {
  const MatchTolerance& tolerance = evaluation.settings.tolerance;
  EvaluationRow row;
  row.setting = setting;
  row.assumption = assumption;
  std::vector<double> seconds;
  for (const PairResult& p : evaluation.pairs) {
    if (setting != "all" && p.setting != setting) continue;
    if (assumption > 1 && !p.in_context) continue;
    const PairInput in =
        matches_within(p, threshold, evaluation.settings.find.selection.min_confidence);
    row.counts.add(assumption == 3 ? count_best_match(in, tolerance)
                                   : count_all_matches(in, tolerance));
    seconds.push_back(p.seconds);
    ++row.pairs;
  }
  row.median_translation_error = median(row.counts.translation_errors);
  row.median_rotation_error = median(row.counts.rotation_errors);
  row.median_seconds = median(seconds);
  return row;
}

namespace {

// One row per bin holding anything, for `assumption`.
template <class Label>
void add_bin_rows(std::vector<std::vector<EvaluationRow>>& per_bin,
                  const std::vector<Counts>& counts, const std::vector<std::size_t>& pairs,
                  int assumption, Label label) {
  for (std::size_t b = 0; b < counts.size(); ++b) {
    if (counts[b].tp + counts[b].fp + counts[b].fn == 0) continue;
    EvaluationRow row;
    row.setting = label(static_cast<int>(b));
    row.assumption = assumption;
    row.counts = counts[b];
    row.pairs = pairs[b];
    row.median_translation_error = median(row.counts.translation_errors);
    row.median_rotation_error = median(row.counts.rotation_errors);
    per_bin[b].push_back(row);
  }
}

// Assumptions 1 (when every pair was searched) and 2, split into `bins` bins: each ground-truth
// instance k of a pair counts in truth_bin(pair, k), each false match in found_bin(pair, pose),
// and label(bin) names a bin's row. Then assumption 3, each in-context pair's best match in the
// bin of its first instance not ignored (the only one, on the real sequences): so a row says how
// often the best match was right for the instances in its bin. Rows by bin, then assumption; bins
// holding nothing are left out.
template <class TruthBin, class FoundBin, class Label>
std::vector<EvaluationRow> rows_by_bin(const Evaluation& evaluation, double threshold, int bins,
                                       TruthBin truth_bin, FoundBin found_bin, Label label) {
  std::vector<std::vector<EvaluationRow>> per_bin(static_cast<std::size_t>(bins));
  for (int assumption = evaluation.settings.in_context_only ? 2 : 1; assumption <= 2;
       ++assumption) {
    std::vector<Counts> counts(bins);
    std::vector<std::size_t> pairs(bins, 0);
    for (const PairResult& p : evaluation.pairs) {
      if (assumption > 1 && !p.in_context) continue;
      const PairInput in =
          matches_within(p, threshold, evaluation.settings.find.selection.min_confidence);
      std::vector<int> truths, founds;
      for (std::size_t k = 0; k < in.truth.size(); ++k) truths.push_back(truth_bin(p, k));
      for (const auto& T : in.found) founds.push_back(found_bin(p, T));
      const std::vector<Counts> split =
          count_all_matches_by(in, truths, founds, bins, evaluation.settings.tolerance);
      for (int b = 0; b < bins; ++b) {
        counts[b].add(split[b]);
        if (split[b].tp + split[b].fp + split[b].fn > 0) ++pairs[b];
      }
    }
    add_bin_rows(per_bin, counts, pairs, assumption, label);
  }
  std::vector<Counts> best(bins);
  std::vector<std::size_t> best_pairs(bins, 0);
  for (const PairResult& p : evaluation.pairs) {
    if (!p.in_context) continue;
    const PairInput in =
        matches_within(p, threshold, evaluation.settings.find.selection.min_confidence);
    for (std::size_t k = 0; k < in.truth.size(); ++k) {
      if (in.is_ignored(k)) continue;
      const int b = truth_bin(p, k);
      if (b >= 0 && b < bins) {
        best[b].add(count_best_match(in, evaluation.settings.tolerance));
        ++best_pairs[b];
      }
      break;
    }
  }
  add_bin_rows(per_bin, best, best_pairs, 3, label);
  std::vector<EvaluationRow> rows;
  for (const auto& bin : per_bin) rows.insert(rows.end(), bin.begin(), bin.end());
  return rows;
}

}  // namespace

std::vector<EvaluationRow> evaluation_rows_by_range(const Evaluation& evaluation,
                                                    std::optional<double> threshold,
                                                    double bin_width) {
  if (!(bin_width > 0.0)) throw Error("the range bins must be wider than 0 m");
  const auto bin_of = [bin_width](const PairResult& p, const Eigen::Isometry3d& pose) {
    return range_bin((pose.translation() - p.sensor_position).norm(), bin_width);
  };
  return rows_by_bin(
      evaluation, threshold.value_or(*evaluation.settings.find.selection.threshold),
      static_cast<int>(std::ceil(10.0 / bin_width)),  // up to 10 m: beyond any depth sensor
      [&](const PairResult& p, std::size_t k) { return bin_of(p, p.truth[k]); }, bin_of,
      [bin_width](int b) { return range_bin_label(b, bin_width); });
}

int range_bin(double range, double bin_width) {
  return static_cast<int>(std::floor(range / bin_width));
}

std::string range_bin_label(int bin, double bin_width) {
  char label[32];
  std::snprintf(label, sizeof(label), "%.1f-%.1f m", bin * bin_width, (bin + 1) * bin_width);
  return label;
}

int hidden_bin(double hidden, double bin_width) {
  const int bins = static_cast<int>(std::ceil(1.0 / bin_width - 1e-9));
  return std::min(static_cast<int>(std::floor(hidden / bin_width)), bins - 1);
}

std::string hidden_bin_label(int bin, double bin_width) {
  char label[32];
  std::snprintf(label, sizeof(label), "%.0f-%.0f%% hidden", 100.0 * bin * bin_width,
                100.0 * std::min(1.0, (bin + 1) * bin_width));
  return label;
}

bool records_hidden_fractions(const Evaluation& evaluation) {
  return std::any_of(evaluation.pairs.begin(), evaluation.pairs.end(),
                     [](const PairResult& p) { return !p.truth_hidden.empty(); });
}

std::vector<EvaluationRow> evaluation_rows_by_hidden(const Evaluation& evaluation,
                                                     std::optional<double> threshold,
                                                     double bin_width) {
  if (!(bin_width > 0.0 && bin_width <= 1.0))
    throw Error("the hidden-fraction bins must be wider than 0 and at most 1");
  if (!records_hidden_fractions(evaluation)) {
    throw Error("dataset '" + evaluation.dataset +
                "' records no hidden fraction of its instances (--by range works on any dataset)");
  }
  const int bins = static_cast<int>(std::ceil(1.0 / bin_width - 1e-9));
  return rows_by_bin(
      evaluation, threshold.value_or(*evaluation.settings.find.selection.threshold), bins,
      [&](const PairResult& p, std::size_t k) {
        if (k >= p.truth_hidden.size()) return -1;  // a pair without the record
        return hidden_bin(p.truth_hidden[k], bin_width);
      },
      [](const PairResult&, const Eigen::Isometry3d&) { return -1; },
      [bin_width](int b) { return hidden_bin_label(b, bin_width); });
}

double azimuth_to_nearest_view(const PairResult& pair, const Eigen::Isometry3d& box_pose) {
  const Eigen::Isometry3d T_scene_capture = box_pose * pair.capture_box.inverse();
  const Eigen::Vector3d up = (T_scene_capture.linear() * pair.landmark_up).normalized();
  const Eigen::Vector3d centre = box_pose.translation();
  const auto flat = [&](const Eigen::Vector3d& to) {
    const Eigen::Vector3d d = to - centre;
    return Eigen::Vector3d(d - d.dot(up) * up);
  };
  const Eigen::Vector3d scene = flat(pair.sensor_position);
  double nearest = M_PI;
  for (const Eigen::Vector3d& origin : pair.view_origins) {
    const Eigen::Vector3d view = flat(T_scene_capture * origin);
    nearest = std::min(nearest, std::atan2(scene.cross(view).norm(), scene.dot(view)));
  }
  return nearest;
}

std::vector<EvaluationRow> evaluation_rows_by_views(const Evaluation& evaluation,
                                                    std::optional<double> threshold,
                                                    double bin_degrees) {
  if (!(bin_degrees > 0.0 && bin_degrees <= 180.0))
    throw Error("the azimuth bins must be wider than 0 and at most 180 degrees");
  const int angle_bins = static_cast<int>(std::ceil(180.0 / bin_degrees - 1e-9));
  const int bins = angle_bins * static_cast<int>(kMaxLandmarkViews);
  const auto bin_of = [&](const PairResult& p, const Eigen::Isometry3d& pose) {
    if (p.view_origins.empty()) return -1;
    const double degrees = azimuth_to_nearest_view(p, pose) * 180.0 / M_PI;
    const int angle = std::min(static_cast<int>(std::floor(degrees / bin_degrees)), angle_bins - 1);
    return static_cast<int>(p.view_origins.size() - 1) * angle_bins + angle;
  };
  const auto views_label = [](int views) {
    return std::to_string(views) + (views == 1 ? " view" : " views");
  };
  const double t = threshold.value_or(*evaluation.settings.find.selection.threshold);
  // First each number of views over every azimuth, then by azimuth.
  const auto views_of = [](const PairResult& p, const Eigen::Isometry3d&) {
    return static_cast<int>(p.view_origins.size()) - 1;
  };
  std::vector<EvaluationRow> rows = rows_by_bin(
      evaluation, t, static_cast<int>(kMaxLandmarkViews),
      [&](const PairResult& p, std::size_t k) { return views_of(p, p.truth[k]); }, views_of,
      [&](int b) { return views_label(b + 1); });
  const std::vector<EvaluationRow> by_azimuth = rows_by_bin(
      evaluation, t, bins,
      [&](const PairResult& p, std::size_t k) { return bin_of(p, p.truth[k]); }, bin_of,
      [&](int b) {
        const int angle = b % angle_bins;
        char label[48];
        std::snprintf(label, sizeof(label), ", %.0f-%.0f deg", angle * bin_degrees,
                      std::min(180.0, (angle + 1) * bin_degrees));
        return views_label(b / angle_bins + 1) + label;
      });
  rows.insert(rows.end(), by_azimuth.begin(), by_azimuth.end());
  return rows;
}

std::vector<EvaluationRow> evaluation_rows(const Evaluation& evaluation,
                                           std::optional<double> threshold) {
  const double t = threshold.value_or(*evaluation.settings.find.selection.threshold);
  std::vector<EvaluationRow> rows;
  for (const std::string& setting : evaluation_settings(evaluation)) {
    for (int assumption = evaluation.settings.in_context_only ? 2 : 1; assumption <= 3;
         ++assumption) {
      rows.push_back(evaluation_row(evaluation, setting, assumption, t));
    }
  }
  return rows;
}

}  // namespace lmk
