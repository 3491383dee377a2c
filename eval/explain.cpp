// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/explain.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>

#include "lmk/eval/evaluation_rows.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/statistics.h"
#include "lmk/landmark/landmark_file.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// A candidate of the search again, and what became of it.
struct Candidate {
  const Match* match;
  std::optional<RejectionReason> rejected;  ///< nothing: accepted
};

// What a pair's search again left: every candidate, best first.
std::vector<Candidate> candidates_of(const FindResult& r) {
  std::vector<Candidate> out;
  for (const Match& m : r.matches) out.push_back({&m, std::nullopt});
  for (const Rejection& j : r.rejected) out.push_back({&j.candidate, j.reason});
  for (const Rejection& j : r.suppressed) out.push_back({&j.candidate, j.reason});
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return a.match->error < b.match->error;
  });
  return out;
}

bool within(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& pose, const Symmetry& symmetry,
            const MatchTolerance& tolerance, double factor = 1.0) {
  return translation_error(truth, pose, symmetry) <= factor * tolerance.translation &&
         rotation_error(truth.linear(), pose.linear(), symmetry) <= factor * tolerance.rotation;
}

std::optional<double> finite_or_none(double v) {
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

ExplainedCase case_of(const PairResult& p, bool missed) {
  ExplainedCase c;
  c.scene = p.scene;
  c.landmark = p.landmark;
  c.setting = p.setting;
  c.missed = missed;
  return c;
}

// Everything a pair needs to be explained.
struct FailedPair {
  const PairResult* result;
  const DatasetScene* scene;
  const DatasetLandmark* landmark;
  PairInput input;  ///< matches within the threshold
  std::vector<std::optional<std::size_t>> assigned;
};

// One failed pair searched again, its suppressed candidates kept: why each instance was missed
// and each false match made.
class PairExplainer {
 public:
  PairExplainer(const FailedPair& f, const SceneIndex& index, const LandmarkIndex& landmark,
                const FindSettings& find, const MatchTolerance& tolerance)
      : f_(f),
        p_(*f.result),
        index_(index),
        landmark_(landmark),
        find_(find),
        tolerance_(tolerance),
        settings_(searched_again(find, *f.scene)),
        again_(find_landmark(index, landmark, settings_)),
        all_(candidates_of(again_)),
        capture_box_(landmark.landmark().box) {
    // The best reported match assigned to no instance, and how sure the search was of it.
    for (std::size_t i = 0; i < f.assigned.size(); ++i) {
      if (f.assigned[i] || (best_wrong_ && *best_wrong_ <= p_.found[i].error)) continue;
      best_wrong_ = p_.found[i].error;
      best_wrong_confidence_ = finite_or_none(p_.found[i].confidence.probability);
    }
  }

  std::vector<ExplainedCase> explain() const {
    std::vector<ExplainedCase> out;
    std::vector<char> matched(p_.truth.size(), 0);
    for (const auto& a : f_.assigned)
      if (a) matched[*a] = 1;
    std::vector<std::size_t> suppressed_truths;
    for (std::size_t k = 0; k < p_.truth.size(); ++k) {
      if (matched[k] || f_.input.is_ignored(k)) continue;
      out.push_back(miss(k));
      if (out.back().cause == ExplainCause::suppressed) suppressed_truths.push_back(k);
    }
    for (std::size_t i = 0; i < f_.assigned.size(); ++i) {
      if (!f_.assigned[i]) out.push_back(false_match(i, suppressed_truths));
    }
    return out;
  }

 private:
  static FindSettings searched_again(const FindSettings& find, const DatasetScene& scene) {
    FindSettings settings = pair_search(find, scene);
    settings.execution.keep_suppressed = true;
    return settings;
  }

  // The metric at true instance k, refined from there.
  Match at_truth(std::size_t k) const {
    return score_pose(index_, landmark_, settings_, p_.truth[k] * capture_box_.pose.inverse());
  }

  double range(const Eigen::Isometry3d& pose) const {
    return (pose.translation() - p_.sensor_position).norm();
  }

  // Missed instance k: the fate of the candidates near it decides the cause.
  ExplainedCase miss(std::size_t k) const {
    ExplainedCase c = case_of(p_, true);
    std::vector<const Candidate*> near;
    for (const Candidate& cand : all_) {
      const Eigen::Isometry3d& pose = cand.match->box.pose;
      if (within(p_.truth[k], pose, p_.symmetry, tolerance_)) near.push_back(&cand);
      const double d = translation_error(p_.truth[k], pose, p_.symmetry);
      if (!c.nearest_candidate_translation || d < *c.nearest_candidate_translation) {
        c.nearest_candidate_translation = d;
        c.nearest_candidate_rotation =
            rotation_error(p_.truth[k].linear(), pose.linear(), p_.symmetry);
      }
    }
    std::vector<CandidateFate> fates;
    for (const Candidate* n : near) fates.push_back({n->match->error, n->rejected});
    c.cause = miss_cause(fates, *find_.selection.threshold);
    c.box = Box(p_.truth[k], capture_box_.size);
    c.range = range(p_.truth[k]);
    if (k < p_.truth_hidden.size()) c.hidden = p_.truth_hidden[k];
    const Match refined = at_truth(k);
    c.truth_error = refined.error;
    c.truth_drift_translation = translation_error(p_.truth[k], refined.box.pose, p_.symmetry);
    c.truth_drift_rotation =
        rotation_error(p_.truth[k].linear(), refined.box.pose.linear(), p_.symmetry);
    c.winner_error = best_wrong_;
    c.winner_confidence = best_wrong_confidence_;
    return c;
  }

  // False match i: it displaced a suppressed instance, lies off an instance's pose, or is a
  // look-alike.
  ExplainedCase false_match(std::size_t i,
                            const std::vector<std::size_t>& suppressed_truths) const {
    const FoundBox& found = p_.found[i];
    ExplainedCase c = case_of(p_, false);
    c.box = found.box;
    c.range = range(found.box.pose);
    c.winner_error = found.error;
    c.winner_confidence = finite_or_none(found.confidence.probability);
    if (!p_.truth.empty()) c.truth_error = at_truth(0).error;
    const double radius = find_.selection.nms_radius;
    const bool displaced =
        std::any_of(suppressed_truths.begin(), suppressed_truths.end(), [&](std::size_t k) {
          return (p_.truth[k].translation() - found.box.center()).norm() < radius ||
                 found.box.contains(Eigen::Vector3d(p_.truth[k].translation()));
        });
    const bool on_instance = std::any_of(p_.truth.begin(), p_.truth.end(), [&](const auto& truth) {
      return within(truth, found.box.pose, p_.symmetry, tolerance_, 2.0);
    });
    c.cause = displaced     ? ExplainCause::displaced_truth
              : on_instance ? ExplainCause::off_pose
                            : ExplainCause::look_alike;
    return c;
  }

  const FailedPair& f_;
  const PairResult& p_;
  const SceneIndex& index_;
  const LandmarkIndex& landmark_;
  const FindSettings& find_;
  const MatchTolerance& tolerance_;
  const FindSettings settings_;
  const FindResult again_;
  const std::vector<Candidate> all_;
  const Box& capture_box_;
  std::optional<double> best_wrong_, best_wrong_confidence_;
};

std::vector<ExplainedCase> explain_pair(const FailedPair& f, const SceneIndex& index,
                                        const LandmarkIndex& landmark, const FindSettings& find,
                                        const MatchTolerance& tolerance) {
  return PairExplainer(f, index, landmark, find, tolerance).explain();
}

}  // namespace

const char* to_string(ExplainCause cause) {
  switch (cause) {
    case ExplainCause::no_candidate:
      return "no candidate";
    case ExplainCause::suppressed:
      return "suppressed";
    case ExplainCause::over_threshold:
      return "over threshold";
    case ExplainCause::coverage:
      return "coverage";
    case ExplainCause::empty_space:
      return "empty space";
    case ExplainCause::too_little_shown:
      return "too little shown";
    case ExplainCause::colour_differs:
      return "colour differs";
    case ExplainCause::displaced_truth:
      return "displaced truth";
    case ExplainCause::off_pose:
      return "off pose";
    case ExplainCause::look_alike:
      return "look-alike";
  }
  return "?";
}

ExplainCause miss_cause(const std::vector<CandidateFate>& near, double t) {
  for (const CandidateFate& c : near) {
    if (!c.rejected) return c.error < t ? ExplainCause::suppressed : ExplainCause::over_threshold;
    switch (*c.rejected) {
      case RejectionReason::suppressed_by_a_better_match:
        continue;  // it lost to a better neighbour: the next near one decides
      case RejectionReason::error_above_threshold:
        return ExplainCause::over_threshold;
      case RejectionReason::coverage_too_low:
        return ExplainCause::coverage;
      case RejectionReason::empty_space_occupied:
        return ExplainCause::empty_space;
      case RejectionReason::too_little_shown:
        return ExplainCause::too_little_shown;
      case RejectionReason::colour_differs:
        return ExplainCause::colour_differs;
      // A wrong match was preferred: it held the candidate in its box, or was surer.
      case RejectionReason::inside_a_better_match:
      case RejectionReason::confidence_too_low:
        return ExplainCause::suppressed;
    }
  }
  return near.empty() ? ExplainCause::no_candidate : ExplainCause::suppressed;
}

const std::vector<ExplainCause>& miss_causes() {
  static const std::vector<ExplainCause> causes{
      ExplainCause::no_candidate,  ExplainCause::suppressed,  ExplainCause::over_threshold,
      ExplainCause::coverage,      ExplainCause::empty_space, ExplainCause::too_little_shown,
      ExplainCause::colour_differs};
  return causes;
}

const std::vector<ExplainCause>& false_match_causes() {
  static const std::vector<ExplainCause> causes{ExplainCause::displaced_truth,
                                                ExplainCause::off_pose, ExplainCause::look_alike};
  return causes;
}

std::vector<ExplainedCase> explain_evaluation(
    const std::string& dataset_dir, const Dataset& dataset, const Evaluation& evaluation,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  const FindSettings& find = evaluation.settings.find;  // resolved
  const MatchTolerance& tolerance = evaluation.settings.tolerance;
  std::map<std::string, const DatasetScene*> scenes;
  for (const DatasetScene& s : dataset.scenes) scenes[s.name] = &s;
  std::map<std::string, const DatasetLandmark*> landmarks;
  for (const DatasetLandmark& l : dataset.landmarks) landmarks[l.name] = &l;

  // The pairs with a miss or a false match, scene by scene.
  std::map<std::string, std::vector<FailedPair>> failed;
  std::size_t to_explain = 0;
  for (const PairResult& p : evaluation.pairs) {
    FailedPair f{&p,
                 nullptr,
                 nullptr,
                 matches_within(p, *find.selection.threshold, find.selection.min_confidence),
                 {}};
    f.assigned = assign_matches(f.input, tolerance);
    const Counts counts = count_all_matches(f.input, tolerance);
    if (counts.fn == 0 && counts.fp == 0) continue;
    const auto scene = scenes.find(p.scene);
    const auto landmark = landmarks.find(p.landmark);
    if (scene == scenes.end() || landmark == landmarks.end()) {
      throw Error("explain: the evaluation's pair " + p.scene + " x " + p.landmark +
                  " is not in dataset '" + dataset.name + "'");
    }
    f.scene = scene->second;
    f.landmark = landmark->second;
    failed[p.scene].push_back(std::move(f));
    ++to_explain;
  }

  std::map<std::string, std::unique_ptr<Landmark>> loaded;
  std::map<std::string, std::unique_ptr<LandmarkIndex>> indexes;
  const FindSettings landmark_settings = pair_search(find, DatasetScene());
  std::vector<ExplainedCase> cases;
  std::atomic<std::size_t> done{0};
  for (const auto& scene_pairs : failed) {
    // A named reference, not a structured binding: C++17 lambdas cannot capture bindings (clang).
    const std::vector<FailedPair>& pairs = scene_pairs.second;
    for (const FailedPair& f : pairs) {
      if (indexes.count(f.landmark->name)) continue;
      loaded[f.landmark->name] = std::make_unique<Landmark>(
          load_landmark((fs::path(dataset_dir) / f.landmark->file).string()));
      indexes[f.landmark->name] = std::make_unique<LandmarkIndex>(
          LandmarkIndex::borrowing(*loaded[f.landmark->name], landmark_settings));
    }
    const DatasetScene& scene = *pairs.front().scene;
    const PointCloud cloud = read_cloud((fs::path(dataset_dir) / scene.file).string());
    const SceneIndex index(cloud, pair_search(find, scene).scene);
    std::vector<std::vector<ExplainedCase>> per_pair(pairs.size());
    tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t i) {
      per_pair[i] =
          explain_pair(pairs[i], index, *indexes.at(pairs[i].landmark->name), find, tolerance);
      if (progress) progress(++done, to_explain);
    });
    for (auto& c : per_pair) cases.insert(cases.end(), c.begin(), c.end());
  }
  // Dataset order: as the evaluation lists its pairs.
  std::map<std::pair<std::string, std::string>, std::size_t> order;
  for (std::size_t i = 0; i < evaluation.pairs.size(); ++i)
    order[{evaluation.pairs[i].scene, evaluation.pairs[i].landmark}] = i;
  std::stable_sort(cases.begin(), cases.end(), [&](const ExplainedCase& a, const ExplainedCase& b) {
    return order[{a.scene, a.landmark}] < order[{b.scene, b.landmark}];
  });
  return cases;
}

namespace {

// The rows of cause_rows(): each case counts in group_of(case) (none: in "all" only) and in "all",
// groups in the order of `sorted`.
std::vector<CauseRow> grouped_cause_rows(
    std::vector<const ExplainedCase*> sorted,
    const std::function<std::optional<std::string>(const ExplainedCase&)>& group_of) {
  std::map<std::string, std::size_t> index;
  std::vector<CauseRow> rows;
  const auto row = [&](const std::string& group) -> CauseRow& {
    auto it = index.find(group);
    if (it == index.end()) {
      it = index.emplace(group, rows.size()).first;
      rows.push_back({group,
                      std::vector<std::size_t>(miss_causes().size(), 0),
                      std::vector<std::size_t>(false_match_causes().size(), 0),
                      {},
                      {},
                      {}});
    }
    return rows[it->second];
  };
  std::map<std::string, std::vector<double>> truth_errors, winner_errors, winner_confidences;
  for (const ExplainedCase* c : sorted) {
    std::vector<std::string> groups{"all"};
    if (const std::optional<std::string> g = group_of(*c)) groups.insert(groups.begin(), *g);
    for (const std::string& group : groups) {
      CauseRow& r = row(group);
      const auto& causes = c->missed ? miss_causes() : false_match_causes();
      const auto k = static_cast<std::size_t>(std::find(causes.begin(), causes.end(), c->cause) -
                                              causes.begin());
      (c->missed ? r.missed : r.false_matches).at(k) += 1;
      if (c->missed && c->truth_error) truth_errors[group].push_back(*c->truth_error);
      if (c->missed && c->winner_error) winner_errors[group].push_back(*c->winner_error);
      if (c->winner_confidence) winner_confidences[group].push_back(*c->winner_confidence);
    }
  }
  // "all" last.
  std::stable_partition(rows.begin(), rows.end(),
                        [](const CauseRow& r) { return r.group != "all"; });
  for (CauseRow& r : rows) {
    if (!truth_errors[r.group].empty()) r.median_truth_error = median(truth_errors[r.group]);
    if (!winner_errors[r.group].empty()) r.median_winner_error = median(winner_errors[r.group]);
    if (!winner_confidences[r.group].empty()) {
      r.median_winner_confidence = median(winner_confidences[r.group]);
    }
  }
  return rows;
}

// The cases sorted by `key`, stably.
template <class Key>
std::vector<const ExplainedCase*> sorted_by(const std::vector<ExplainedCase>& cases, Key key) {
  std::vector<const ExplainedCase*> sorted;
  for (const ExplainedCase& c : cases) sorted.push_back(&c);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [&](const auto* a, const auto* b) { return key(*a) < key(*b); });
  return sorted;
}

}  // namespace

std::vector<CauseRow> cause_rows(const std::vector<ExplainedCase>& cases,
                                 std::optional<double> bin_width) {
  if (!bin_width) {
    return grouped_cause_rows(sorted_by(cases, [](const ExplainedCase&) { return 0; }),
                              [](const ExplainedCase& c) { return c.setting; });
  }
  const double w = *bin_width;
  return grouped_cause_rows(sorted_by(cases, [](const ExplainedCase& c) { return c.range; }),
                            [w](const ExplainedCase& c) -> std::optional<std::string> {
                              return range_bin_label(range_bin(c.range, w), w);
                            });
}

std::vector<CauseRow> cause_rows_by_hidden(const std::vector<ExplainedCase>& cases,
                                           double bin_width) {
  const auto bin = [bin_width](const ExplainedCase& c) {
    return c.hidden ? hidden_bin(*c.hidden, bin_width) : -1;
  };
  return grouped_cause_rows(sorted_by(cases, bin),
                            [&](const ExplainedCase& c) -> std::optional<std::string> {
                              if (!c.hidden) return std::nullopt;
                              return hidden_bin_label(bin(c), bin_width);
                            });
}

TextTable cause_table(const std::vector<CauseRow>& rows, const std::string& metric) {
  TextTable table;
  table.header = {""};
  for (ExplainCause c : miss_causes())
    table.header.push_back(std::string("missed: ") + to_string(c));
  for (ExplainCause c : false_match_causes())
    table.header.push_back(std::string("false: ") + to_string(c));
  table.header.push_back("at truth");
  table.header.push_back("wrong winner");
  table.header.push_back("its confidence");
  table.numeric.assign(table.header.size(), true);
  table.numeric[0] = false;
  const auto error = [&](const std::optional<double>& v) {
    return v ? format_error(*v, metric) : std::string("-");
  };
  for (const CauseRow& r : rows) {
    std::vector<std::string> line{r.group};
    for (std::size_t n : r.missed) line.push_back(std::to_string(n));
    for (std::size_t n : r.false_matches) line.push_back(std::to_string(n));
    line.push_back(error(r.median_truth_error));
    line.push_back(error(r.median_winner_error));
    line.push_back(format_optional(r.median_winner_confidence, 2));
    table.rows.push_back(std::move(line));
  }
  return table;
}

}  // namespace lmk
