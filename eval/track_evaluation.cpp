// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/track_evaluation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/text_table.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/statistics.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/internal/confidence_json.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// The ground truth of `landmark` in `scene`: its one instance when in view, none when away, and
// unknown when the dataset lists no pair for them (a real frame whose poses were left unchecked).
FrameTruth truth_of(const DatasetScene& scene, const std::string& landmark,
                    std::optional<Eigen::Isometry3d>& instance) {
  for (const DatasetPair& p : scene.pairs) {
    if (p.landmark != landmark) continue;
    if (p.instances.empty()) return FrameTruth::away;
    instance = p.instances.front();
    const bool hidden = !p.hidden.empty() && p.hidden.front() >= kIgnoredHiddenFraction;
    return hidden ? FrameTruth::away : FrameTruth::in_view;
  }
  return FrameTruth::unknown;
}

bool within(const TrackedFrame& f, const TrackTolerance& t) {
  return f.truth == FrameTruth::in_view && f.has_pose && f.translation_error <= t.translation &&
         f.rotation_error <= t.rotation;
}

// The sequence's counts, carry and re-find from its frames.
void score(SequenceResult& r, const TrackTolerance& tolerance) {
  for (const TrackedFrame& f : r.frames) {
    if (f.truth == FrameTruth::in_view) {
      ++r.in_view;
      if (within(f, tolerance)) ++r.within;
      if (!f.has_pose) ++r.lost_in_view;
      if (f.has_pose && !within(f, tolerance)) ++r.wrong_in_view;
    }
    if (f.truth == FrameTruth::away && f.has_pose) ++r.pose_while_away;
  }
  if (!r.carry) return;
  for (std::size_t k = r.carry->from; k < r.frames.size(); ++k) {
    const TrackedFrame& f = r.frames[k];
    // Noticed: it no longer claims to follow the landmark where it was, or it is right again.
    if (f.state != TrackState::tracking || within(f, tolerance)) {
      r.carry_noticed_after = k - r.carry->from;
      break;
    }
  }
  for (std::size_t k = r.carry->back; k < r.frames.size(); ++k) {
    if (within(r.frames[k], tolerance)) {
      r.refound_after = k - r.carry->back;
      break;
    }
  }
}

// The dataset's scenes by name.
using ScenesByName = std::map<std::string, const DatasetScene*>;

SequenceResult follow(const std::string& dir, const Dataset& dataset, const ScenesByName& scenes,
                      const TrackSequence& sequence, const TrackEvaluationOptions& options,
                      const std::function<void()>& frame_done) {
  const auto landmark_entry =
      std::find_if(dataset.landmarks.begin(), dataset.landmarks.end(),
                   [&](const DatasetLandmark& l) { return l.name == sequence.landmark; });
  auto landmark =
      std::make_shared<Landmark>(load_landmark((fs::path(dir) / landmark_entry->file).string()));
  TrackSettings settings = options.track;
  if (const auto& up = scenes.at(sequence.frames.front())->up) settings.find.scene.up = up;
  Tracker tracker({landmark}, settings);

  SequenceResult r;
  r.name = sequence.name;
  r.landmark = sequence.landmark;
  r.carry = sequence.carry;
  r.pose_check = sequence.pose_check;
  for (const std::string& name : sequence.frames) {
    const DatasetScene& scene = *scenes.at(name);
    const TrackedLandmark now =
        tracker.update(read_cloud((fs::path(dir) / scene.file).string())).front();
    TrackedFrame f;
    f.state = now.state;
    f.seconds = now.seconds;
    f.has_pose = now.match.has_value();
    if (f.has_pose) {
      f.pose = now.match->box.pose;
      f.error = now.match->error;
      f.confidence = now.match->confidence.probability;
      f.freedom = now.match->confidence.freedom;
    }
    std::optional<Eigen::Isometry3d> truth;
    f.truth = truth_of(scene, sequence.landmark, truth);
    if (f.has_pose && truth) {
      f.translation_error =
          translation_error(*truth, now.match->box.pose, landmark_entry->symmetry);
      f.rotation_error =
          rotation_error(truth->linear(), now.match->box.pose.linear(), landmark_entry->symmetry);
    }
    r.frames.push_back(f);
    frame_done();
  }
  score(r, options.tolerance);
  return r;
}

std::string frames_after(const std::optional<std::size_t>& n) {
  return n ? std::to_string(*n) : "never";
}

std::string ms(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", 1e3 * seconds);
  return text;
}

std::vector<double> frame_seconds(const SequenceResult& r) {
  std::vector<double> s;
  for (const TrackedFrame& f : r.frames) s.push_back(f.seconds);
  return s;
}

}  // namespace

std::size_t TrackEvaluation::in_view() const {
  std::size_t n = 0;
  for (const SequenceResult& s : sequences) n += s.in_view;
  return n;
}

std::size_t TrackEvaluation::within() const {
  std::size_t n = 0;
  for (const SequenceResult& s : sequences) n += s.within;
  return n;
}

double TrackEvaluation::percentile_seconds(double q) const {
  std::vector<double> all;
  for (const SequenceResult& s : sequences) {
    const std::vector<double> v = frame_seconds(s);
    all.insert(all.end(), v.begin(), v.end());
  }
  return percentile(all, q);
}

double TrackEvaluation::median_seconds() const { return percentile_seconds(0.5); }

TrackEvaluation evaluate_tracking(const std::string& dir, const TrackEvaluationOptions& options) {
  const Stopwatch stopwatch;
  const Dataset dataset = load_dataset(dir, options.files);
  std::vector<TrackSequence> sequences = load_track_sequences(dir, dataset);
  sequences.erase(std::remove_if(sequences.begin(), sequences.end(),
                                 [&](const TrackSequence& s) {
                                   return s.name.find(options.only) == std::string::npos;
                                 }),
                  sequences.end());
  if (sequences.empty()) throw Error("eval-track: no sequence's name holds '" + options.only + "'");
  std::size_t total = 0, done = 0;
  for (const TrackSequence& s : sequences) total += s.frames.size();
  TrackEvaluation evaluation;
  evaluation.dataset = dataset.name;
  evaluation.tolerance = options.tolerance;
  ScenesByName scenes;
  for (const DatasetScene& s : dataset.scenes) scenes[s.name] = &s;
  for (const TrackSequence& s : sequences) {
    evaluation.sequences.push_back(follow(dir, dataset, scenes, s, options, [&] {
      if (options.progress) options.progress(++done, total);
    }));
  }
  evaluation.seconds = stopwatch.seconds();
  return evaluation;
}

std::string tracking_report(const TrackEvaluation& e) {
  TextTable table;
  table.header = {"sequence",       "in view",       "within",   "lost",      "wrong",
                  "pose when away", "carry noticed", "re-found", "median ms", "p95 ms"};
  table.numeric = {false, true, true, true, true, true, true, true, true, true};
  for (const SequenceResult& s : e.sequences) {
    const std::vector<double> seconds = frame_seconds(s);
    table.rows.push_back({s.name, std::to_string(s.in_view), std::to_string(s.within),
                          std::to_string(s.lost_in_view), std::to_string(s.wrong_in_view),
                          std::to_string(s.pose_while_away),
                          s.carry ? frames_after(s.carry_noticed_after) : "-",
                          s.carry ? frames_after(s.refound_after) : "-",
                          ms(percentile(seconds, 0.5)), ms(percentile(seconds, 0.95))});
  }
  char summary[512];
  const double share = e.in_view() ? static_cast<double>(e.within()) / e.in_view() : 0.0;
  std::snprintf(summary, sizeof summary,
                "%zu of %zu frames in view tracked within %.0f mm / %.0f degrees (%.1f%%); per "
                "landmark and frame median %s ms, 95th percentile %s ms; %.1f s\n",
                e.within(), e.in_view(), 1e3 * e.tolerance.translation,
                e.tolerance.rotation * 180.0 / M_PI, 100.0 * share, ms(e.median_seconds()).c_str(),
                ms(e.percentile_seconds(0.95)).c_str(), e.seconds);
  return table.plain() + summary;
}

std::string tracking_json(const TrackEvaluation& e) {
  using nlohmann::json;
  json sequences = json::array();
  for (const SequenceResult& s : e.sequences) {
    json frames = json::array();
    for (const TrackedFrame& f : s.frames) {
      static const char* const truths[] = {"in view", "away", "unknown"};
      json j = {{"state", to_string(f.state)},
                {"truth", truths[static_cast<int>(f.truth)]},
                {"seconds", f.seconds}};
      if (f.has_pose) {
        j.update(detail::pose_to_json(f.pose));
        j["error"] = f.error;
        j["confidence"] = detail::finite_or_null(f.confidence);  // NaN: no calibration applied
        j["freedom_m"] = detail::finite_or_null(f.freedom);
      }
      if (f.has_pose && f.truth == FrameTruth::in_view) {
        j["translation_error_m"] = f.translation_error;
        j["rotation_error_rad"] = f.rotation_error;
      }
      frames.push_back(j);
    }
    const auto optional = [](const std::optional<std::size_t>& n) {
      return n ? json(*n) : json(nullptr);
    };
    json j = {{"name", s.name},
              {"landmark", s.landmark},
              {"in_view", s.in_view},
              {"within", s.within},
              {"lost_in_view", s.lost_in_view},
              {"wrong_in_view", s.wrong_in_view},
              {"pose_while_away", s.pose_while_away},
              {"carry_noticed_after", optional(s.carry_noticed_after)},
              {"refound_after", optional(s.refound_after)},
              {"frames", frames}};
    if (s.carry) j["carry"] = {{"from", s.carry->from}, {"back", s.carry->back}};
    if (s.pose_check) {
      j["pose_check"] = {{"translation_m", s.pose_check->translation},
                         {"rotation_rad", s.pose_check->rotation}};
    }
    sequences.push_back(j);
  }
  return json({{"dataset", e.dataset},
               {"tolerance",
                {{"translation_m", e.tolerance.translation},
                 {"rotation_rad", e.tolerance.rotation}}},
               {"in_view", e.in_view()},
               {"within", e.within()},
               {"median_seconds", e.median_seconds()},
               {"p95_seconds", e.percentile_seconds(0.95)},
               {"seconds", e.seconds},
               {"sequences", sequences}})
             .dump(1) +
         "\n";
}

}  // namespace lmk
