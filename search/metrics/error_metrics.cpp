// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/metrics/error_metrics.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/metrics/coarse_scores.h"
#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/search/metrics/sensor_metric.h"
#include "lmk/search/scene_index.h"

namespace lmk {
namespace {

// Where Algorithm 2's second loop looks for the nearest scene point of an unvisited landmark point,
// and the largest distance it may add: the two choices in which the metric variants differ.
struct LandmarkTermRule {
  bool in_box_only;  ///< search only the scene points inside the candidate box
  double cap;        ///< distances at or above this are not counted
};

// CandidateError (Algorithm 2). Lines 5-10: each scene point in the candidate box adds its distance
// to the nearest landmark point and marks that point visited; scene points are mapped into the
// capture frame. Lines 11-17: each unvisited landmark point adds its distance to the nearest scene
// point, searched as `rule` says.
ErrorTerms candidate_error(const SceneView& scene, const LandmarkView& landmark,
                           const Eigen::Isometry3d& T_scene_capture, const LandmarkTermRule& rule) {
  ErrorTerms terms;
  const Indices in_box = scene_points_in_box(scene, landmark.box.transformed(T_scene_capture));
  terms.scene_points_in_box = in_box.size();
  std::vector<char> visited(landmark.points.size(), 0);
  const Eigen::Isometry3f T_capture_scene = T_scene_capture.inverse().cast<float>();
  for (Index i : in_box) {
    const auto nearest = landmark.tree.nearest(T_capture_scene * scene.points().points[i]);
    if (!nearest) continue;
    terms.scene_to_landmark_sum += std::sqrt(nearest->squared_distance);
    ++terms.scene_to_landmark_count;
    visited[nearest->index] = 1;
  }

  std::optional<KdTree> box_tree;
  if (rule.in_box_only) box_tree.emplace(scene.points().select(in_box));
  const KdTree& target = box_tree ? *box_tree : scene.tree();
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (visited[j]) continue;
    const auto nearest = target.nearest(T * landmark.points.points[j]);
    if (!nearest) continue;
    const double d = std::sqrt(nearest->squared_distance);
    if (d >= rule.cap) continue;
    terms.landmark_to_scene_sum += d;
    ++terms.landmark_to_scene_count;
  }
  terms.finish();
  return terms;
}

// Algorithm 2 exactly: the whole scene, no cap.
ErrorTerms paper_metric(const SceneView& scene, const LandmarkView& landmark,
                        const Eigen::Isometry3d& T_scene_capture) {
  return candidate_error(scene, landmark, T_scene_capture,
                         {false, std::numeric_limits<double>::infinity()});
}

// The authors' code (rapid_perception): only the scene points inside the box, under 5 cm.
ErrorTerms rapid_metric(const SceneView& scene, const LandmarkView& landmark,
                        const Eigen::Isometry3d& T_scene_capture) {
  return candidate_error(scene, landmark, T_scene_capture, {true, 0.05});
}

}  // namespace

const PointCloud& SceneView::points() const { return index.fine(); }
const KdTree& SceneView::tree() const { return index.fine_tree(); }

void ErrorTerms::finish() {
  const std::size_t count = scene_to_landmark_count + landmark_to_scene_count;
  error = count == 0 ? std::numeric_limits<double>::infinity()
                     : range_scale * (scene_to_landmark_sum + landmark_to_scene_sum) /
                               static_cast<double>(count) +
                           (colour ? colour->penalty : 0.0);
}

Indices scene_points_in_box(const SceneView& scene, const Box& box) {
  // Every point of the box lies within its half-diagonal of the centre.
  const float radius = static_cast<float>(0.5 * box.size.norm()) * (1.0f + 1e-6f);
  Indices out;
  for (const Neighbor& n : scene.tree().radius(box.center().cast<float>(), radius)) {
    if (box.contains(scene.points().points[n.index])) out.push_back(n.index);
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

// A metric in metres, shown in millimetres, ranked and pruned by its surface distance.
ErrorMetric in_metres(std::string name, std::string description, ErrorMetricFunction evaluate,
                      double default_threshold, bool hides_occluded = false) {
  ErrorMetric m;
  m.name = std::move(name);
  m.description = std::move(description);
  m.evaluate = std::move(evaluate);
  m.default_threshold = default_threshold;
  m.coarse_score = detail::surface_distance_coarse_score(hides_occluded);
  m.hides_occluded = hides_occluded;
  return m;
}

// The sensor metric: residuals in sigma of the depth noise, its own fit as its coarse score, pruned
// at twice its default threshold. It tests empty space beyond the noise, which far away exceeds
// the landmark distance field's band, so it needs the empty voxels' distances; its projective
// visibility hides what the scene's sensor could not see.
ErrorMetric in_sigma(std::string name, std::string description, ErrorMetricFunction evaluate) {
  ErrorMetric m;
  m.name = std::move(name);
  m.description = std::move(description);
  m.evaluate = std::move(evaluate);
  m.default_threshold = 1.0;
  m.display = {1.0, 2, "sigma", "sd", "sd"};
  m.coarse_score = detail::sensor_coarse_score();
  m.prune_ratio = 2.0;
  m.noise_normalised = true;
  m.needs_empty_distances = true;
  m.hides_occluded = true;
  return m;
}

std::vector<ErrorMetric> builtin_metrics() {
  return {
      in_metres("paper",
                "Algorithm 2 of Huang & Cakmak: mean of scene->landmark distances over the scene "
                "points in the box and landmark->scene distances (whole scene) over the unvisited "
                "landmark points",
                paper_metric, 0.0055),
      in_metres("rapid",
                "the authors' code: as 'paper', but the landmark->scene term searches only the "
                "scene points in the box and counts only distances under 5 cm",
                rapid_metric, 0.0055),
      in_metres("vdb",
                "as 'paper', with grid lookups: scene points in the box against the landmark's "
                "distance field, unvisited landmark points against the scene's, both capped at "
                "their bands",
                vdb_metric, 0.0055),
      in_metres("visibility",
                "visibility-aware: every landmark point's distance to the scene surface (capped), "
                "plus the landmark's observed-empty voxels that the scene occupies; occluded space "
                "is not penalised",
                visibility_metric, 0.006),
      in_metres("projective",
                "as 'visibility', seen from the scene's sensor: landmark points behind a nearer "
                "scene surface are hidden and count neither way, over at least half of the points",
                projective_metric, 0.006, /*hides_occluded=*/true),
      in_sigma("sensor",
               "sensor-aware: residuals in units of the depth noise expected at each point's "
               "capture and scene depths; points the scene's sensor could not see are unknown, "
               "points it saw through count against; the free space is checked through the "
               "scene's depth image too",
               sensor_metric),
  };
}

std::vector<ErrorMetric>& registry() {
  static std::vector<ErrorMetric> metrics = builtin_metrics();
  return metrics;
}

// Each library $LMK_METRIC_PLUGINS names, opened and asked to register its metrics. A library
// stays loaded for the process's life: its metrics' functions live in it.
void load_metric_plugins() {
  const char* list = std::getenv(kMetricPluginsVariable);
  if (!list) return;
  std::stringstream paths(list);
  std::string path;
  while (std::getline(paths, path, ':')) {
    if (path.empty()) continue;
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) {
      throw Error(std::string(kMetricPluginsVariable) + ": cannot load '" + path +
                  "': " + dlerror());
    }
    using Register = void (*)();
    const auto register_metrics =
        reinterpret_cast<Register>(dlsym(library, "lmk_register_error_metrics"));
    if (!register_metrics) {
      throw Error(std::string(kMetricPluginsVariable) + ": '" + path +
                  "' exports no lmk_register_error_metrics()");
    }
    register_metrics();
  }
}

}  // namespace

const std::vector<ErrorMetric>& error_metrics() {
  // Loaded once; a failed load throws to the caller and is tried again by the next.
  static std::once_flag plugins_loaded;
  std::call_once(plugins_loaded, load_metric_plugins);
  return registry();
}

void register_error_metric(ErrorMetric metric) {
  const std::string what = "register_error_metric('" + metric.name + "'): ";
  if (metric.name.empty()) throw Error("register_error_metric: the metric has no name");
  // A plugin's words reach the terminal (lmk metrics) and the reports: printable text only.
  if (!is_printable_text(metric.name) || metric.name.size() > kMaxMetricName)
    throw Error("register_error_metric('" + printable(metric.name) +
                "'): the name must be printable text of at most " + std::to_string(kMaxMetricName) +
                " bytes");
  const ErrorDisplay& d = metric.display;
  for (const std::string& words : {metric.description, d.label, d.column, d.json_unit}) {
    if (!is_printable_text(words))
      throw Error(what + "the description and the display's units must be printable text");
  }
  if (!(d.scale > 0.0 && std::isfinite(d.scale)) || d.decimals < 0 || d.decimals > 9)
    throw Error(what + "the display's scale must be positive and finite, its decimals 0 to 9");
  if (!metric.evaluate) throw Error(what + "no evaluate function");
  static_assert(kMaxMetricThreshold == 1e6 && kMaxPruneRatio == 1e3, "the messages below say so");
  if (!(metric.default_threshold > 0.0 && metric.default_threshold <= kMaxMetricThreshold)) {
    throw Error(what + "the default threshold must be positive and at most 1e6");
  }
  if (!(metric.prune_ratio >= 1.0 && metric.prune_ratio <= kMaxPruneRatio)) {
    throw Error(what + "the prune ratio must be 1 to 1000 (a coarse score below the threshold " +
                "cannot drop a match)");
  }
  std::vector<ErrorMetric>& metrics = registry();
  for (const ErrorMetric& m : metrics) {
    if (m.name == metric.name) throw Error(what + "the name is taken");
  }
  metrics.push_back(std::move(metric));
}

std::vector<float> empty_space_distances(const Landmark& landmark, const KdTree& tree) {
  const std::vector<Eigen::Vector3f>& centres = landmark.empty_space.centres();
  std::vector<float> out(centres.size(), std::numeric_limits<float>::infinity());
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (const auto n = tree.nearest(centres[i])) out[i] = std::sqrt(n->squared_distance);
  }
  return out;
}

std::string format_error(double value, const ErrorMetric& metric) {
  const ErrorDisplay& d = metric.display;
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f %s", d.decimals, d.scale * value, d.label.c_str());
  return text;
}

std::string format_error(double value, const std::string& name) {
  return format_error(value, find_error_metric(name));
}

std::vector<std::string> error_metric_names() {
  std::vector<std::string> names;
  for (const ErrorMetric& m : error_metrics()) names.push_back(m.name);
  return names;
}

const ErrorMetric& find_error_metric(const std::string& name) {
  std::string known;
  for (const ErrorMetric& m : error_metrics()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw Error("unknown error metric '" + name + "' (known: " + known + ")");
}

}  // namespace lmk
