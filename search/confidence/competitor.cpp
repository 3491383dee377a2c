// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/confidence/competitor.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "lmk/geometry/frame_noise.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/slide_check.h"
#include "lmk/registration/icp.h"
#include "lmk/search/detail/selection_tests.h"
#include "lmk/search/metrics/sensor_metric.h"

namespace lmk::detail {
namespace {

// Landmark points enough to measure support, freedom and symmetry: a few hundred fix a pose as
// well as all of them (the fast search's coarse score uses 400 too).
constexpr std::size_t kMaxEvidencePoints = 400;

std::vector<Eigen::Vector3f> thinned(const PointCloud& cloud, std::size_t cap) {
  std::vector<Eigen::Vector3f> out;
  const std::size_t step = std::max<std::size_t>(1, (cloud.size() + cap - 1) / cap);
  for (std::size_t i = 0; i < cloud.size(); i += step) {
    if (is_finite(cloud.points[i])) out.push_back(cloud.points[i]);
  }
  return out;
}

// Whether `other` puts the landmark's points where `match` puts them, though turned: a turn about
// an axis the shape is symmetric about (a bowl, a ball), which no search and no evaluation can
// tell from the match. The mean distance from each point moved by the relative motion to the
// nearest landmark point stays within half a coarse leaf.
bool same_surface(const ConfidenceInput& in, const std::vector<Eigen::Vector3f>& points,
                  const Eigen::Isometry3d& T_match, const Eigen::Isometry3d& T_other) {
  if (points.empty()) return false;
  const Eigen::Isometry3f M = (T_match.inverse() * T_other).cast<float>();
  double sum = 0.0;
  for (const Eigen::Vector3f& p : points) {
    const auto n = in.landmark_tree.nearest(M * p);
    if (!n) return false;
    sum += std::sqrt(static_cast<double>(n->squared_distance));
  }
  return sum / static_cast<double>(points.size()) < 0.5 * in.index.settings().coarse_leaf;
}

// Whether `other` puts a flat landmark's plane where `match` puts it (its normal within
// kSamePoseAngle, its centre within kSamePoseDistance of the match's plane): the same patch of the
// same surface, wherever on it.
bool same_plane(const Eigen::Vector3d& normal, const Match& match, const Match& other) {
  const Eigen::Vector3d n_match = match.T_scene_capture.linear() * normal;
  const Eigen::Vector3d n_other = other.T_scene_capture.linear() * normal;
  const double off_plane = std::abs(n_match.dot(other.box.center() - match.box.center()));
  return std::abs(n_match.dot(n_other)) > std::cos(kSamePoseAngle) && off_plane < kSamePoseDistance;
}

struct Rivals {
  const Match* local = nullptr;      ///< best slide or turn
  const Match* elsewhere = nullptr;  ///< best look-alike
};

Rivals find_rivals(const ConfidenceInput& in, const Match& match,
                   const std::vector<const Match*>& pool,
                   const std::vector<Eigen::Vector3f>& points) {
  Rivals r;
  const Eigen::Vector3d centre = match.box.center();
  for (const Match* c : pool) {
    if (!std::isfinite(c->error) || !plausible_alternative(*c, in.selection)) continue;
    const double distance = (c->box.center() - centre).norm();
    const double angle =
        rotation_angle_between(match.T_scene_capture.linear(), c->T_scene_capture.linear());
    if (distance < kSamePoseDistance &&
        (angle < kSamePoseAngle ||
         same_surface(in, points, match.T_scene_capture, c->T_scene_capture))) {
      continue;  // the same pose, as the evaluation would count it
    }
    if (in.flat_normal && same_plane(*in.flat_normal, match, *c)) continue;
    const Match*& slot = match.box.contains(c->box.center()) ? r.local : r.elsewhere;
    if (!slot || c->error < slot->error) slot = c;
  }
  return r;
}

Competitor describe_competitor(const Match& match, const Match& rival) {
  Competitor c;
  c.T_scene_capture = rival.T_scene_capture;
  c.box = rival.box;
  c.error = rival.error;
  c.distance = (rival.box.center() - match.box.center()).norm();
  c.angle = rotation_angle_between(match.T_scene_capture.linear(), rival.T_scene_capture.linear());
  if (!match.box.contains(rival.box.center())) {
    c.kind = Competitor::Kind::look_alike;
  } else {
    c.kind = c.distance < kSamePoseDistance ? Competitor::Kind::turn : Competitor::Kind::slide;
  }
  return c;
}

// The landmark's points that the scene supports at the match (a scene surface within the
// coverage's support distance, two fine leaves), with the scene's normals there: their count,
// and the freest motion they allow within the noise (slide_check.h's H on the scene's side).
void measure_support(const ConfidenceInput& in, const Match& match,
                     const std::vector<Eigen::Vector3f>& points, double noise,
                     MatchConfidence& out) {
  const DistanceFieldTarget target(in.index.field(), &in.index.coarse().normals);
  const float support = static_cast<float>(2.0 * in.index.settings().leaf_size);
  const Eigen::Isometry3f T = match.T_scene_capture.cast<float>();
  PointCloud supported;
  supported.normals.reserve(points.size());
  for (const Eigen::Vector3f& p : points) {
    const Eigen::Vector3f q = T * p;
    Eigen::Vector3f nearest, normal;
    if (!target.nearest(q, nearest, normal) || (nearest - q).norm() >= support) continue;
    supported.points.push_back(nearest);
    supported.normals.push_back(normal);
  }
  out.support = supported.size();
  const std::vector<Slide> motions = motion_extents(supported, noise);
  if (!motions.empty()) {
    out.freest = motions.front();
    out.freedom = motions.front().displacement;
  }
}

// The residual sigma of a landmark point against the scene's surface at the match, two ways: the
// sensor model's (DepthNoise::residual_sigma at the capture's and the match's range), which the
// margins, fit and freedom are in units of, and the same sum with the noise measured in the frames
// (issue #59): the scene's in its own frame around the match, the capture's as the capture check
// measured it, each the model's where its frame could not measure it. Returns the model's.
// out.range and out.capture_range (describe_landmark()) set first.
double measure_noise(const ConfidenceInput& in, const Match& match, MatchConfidence& out) {
  const DepthNoise model = in.index.settings().depth_noise();
  out.model_noise = model.residual_sigma(out.capture_range, out.range);
  out.capture_noise = model.measurement_sigma_or(in.landmark.findings.noise, out.capture_range);
  const RangeImage* image = in.index.range_image();
  const MeasuredNoise measured =
      image ? measure_noise_at(*image, match.box.center().cast<float>()) : MeasuredNoise{};
  out.scene_noise_measured = measured.measured();
  out.scene_noise = model.measurement_sigma_or(measured.sigma, out.range);
  out.measured_noise = model.residual_of(out.capture_noise, out.scene_noise);
  return out.model_noise;
}

// The landmark's own figures (its size, its points, how much of it the scene's sensor can see at
// the match) and what its capture found.
void describe_landmark(const ConfidenceInput& in, const Match& match,
                       const std::vector<Eigen::Vector3f>& points, MatchConfidence& out) {
  out.landmark_size = in.landmark.box.size.norm();
  out.landmark_points = in.landmark.points.size();
  out.capture = in.landmark.findings;
  const Eigen::Vector3d centre = in.landmark.box.center();
  out.capture_range = (in.landmark.sensor_origin - centre).norm();
  // The scene's sensor in the capture frame, against every view the landmark was captured from.
  const Eigen::Vector3d sensor =
      match.T_scene_capture.inverse() * in.index.T_scene_sensor().translation();
  const std::vector<Eigen::Vector3d> origins =
      in.landmark.multi_view() ? in.landmark.view_origins
                               : std::vector<Eigen::Vector3d>{in.landmark.sensor_origin};
  for (const Eigen::Vector3d& origin : origins) {
    const double angle = std::acos(
        std::clamp((origin - centre).normalized().dot((sensor - centre).normalized()), -1.0, 1.0));
    if (!(angle >= out.view_change)) out.view_change = angle;
  }
  const RangeImage* image = in.index.range_image();
  if (!image || points.empty()) return;
  // Seen: in the image, with a depth measured there that is not clearly in front of the point
  // (a nearer surface hides it). Two coarse leaves absorb the noise and the landmark's own
  // thickness.
  const double hidden_by = 2.0 * in.index.settings().coarse_leaf;
  const Eigen::Isometry3f T = match.T_scene_capture.cast<float>();
  std::size_t seen = 0;
  for (const Eigen::Vector3f& p : points) {
    const RangeImage::Look look = image->look(T * p);
    if (look.in_view && std::isfinite(look.measured) && look.measured > look.depth - hidden_by)
      ++seen;
  }
  out.seen_fraction = static_cast<double>(seen) / static_cast<double>(points.size());
}

// Probe offsets along one side of a motion: from one same-pose step out to `reach`, half a step
// apart (so that a pose between two probes lies within a quarter step of one), at most
// kMaxProbesPerSide.
constexpr std::size_t kMaxProbesPerSide = 8;

std::vector<double> probe_offsets(double step, double reach) {
  std::vector<double> out;
  for (std::size_t k = 0; k < kMaxProbesPerSide; ++k) {
    const double offset = step * (1.0 + 0.5 * static_cast<double>(k));
    if (offset > reach) break;
    out.push_back(offset);
  }
  return out;
}

// The match moved by `offset` along `freest` (m along its axis, or rad about it), and scored.
Match moved_match(const ConfidenceInput& in, const Match& match, const Slide& freest,
                  double offset) {
  const Eigen::Vector3d axis = freest.axis.normalized();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  if (freest.turn) {
    motion = Eigen::Translation3d(freest.through) * Eigen::AngleAxisd(offset, axis) *
             Eigen::Translation3d(-freest.through);
  } else {
    motion.translation() = offset * axis;
  }
  Match probe;
  probe.T_scene_capture = motion * match.T_scene_capture;
  probe.box = in.landmark.box.transformed(probe.T_scene_capture);
  probe.terms = in.metric.evaluate(SceneView{in.index}, in.view, probe.T_scene_capture);
  probe.error = probe.terms.error;
  return probe;
}

}  // namespace

std::vector<Match> probe_freest_motion(const ConfidenceInput& in, const Match& match,
                                       const MatchConfidence& confidence) {
  const Slide& freest = confidence.freest;
  std::vector<Match> out;
  // A flat landmark moves freely within its plane by design: those moves are no rivals.
  if (in.flat_normal || !(confidence.freedom >= 0.5 * kSamePoseDistance)) return out;
  // A slide as far as the box reaches along it (beyond, the landmark would have left its own
  // box); a turn up to half a revolution either way.
  const Eigen::Vector3d along = match.box.pose.linear().transpose() * freest.axis.normalized();
  const std::vector<double> offsets =
      freest.turn ? probe_offsets(kSamePoseAngle, M_PI)
                  : probe_offsets(kSamePoseDistance, along.cwiseAbs().dot(match.box.size));
  // Both sides' probes scored at once, in parallel: up to 16 evaluations of the metric, which
  // were a search's longest serial step after its candidates.
  const std::size_t n = offsets.size();
  std::vector<Match> probes(2 * n);
  tbb::parallel_for(std::size_t{0}, 2 * n, [&](std::size_t k) {
    probes[k] = moved_match(in, match, freest, (k < n ? 1.0 : -1.0) * offsets[k % n]);
  });
  for (const std::size_t first : {std::size_t{0}, n}) {
    // A rival is a pose where the landmark fits again, not the slope of the match's own fit: a
    // probe whose error is no higher than its neighbours' along the motion (the match itself the
    // first neighbour; the last probe, while the error still falls, stands for what lies beyond).
    const Match* line = probes.data() + first;
    for (std::size_t k = 0; k < n; ++k) {
      const double before = k == 0 ? match.error : line[k - 1].error;
      const bool after_ok = k + 1 == n || line[k].error <= line[k + 1].error;
      if (line[k].error <= before && after_ok) out.push_back(line[k]);
    }
  }
  return out;
}

double empty_space_intrusion(const ErrorTerms& t, const SelectionSettings& s) {
  if (!t.empty_space) return 0.0;
  const double allowed = s.max_empty_space_violation * static_cast<double>(t.empty_space->probes);
  if (!(allowed > 0.0)) return 0.0;
  return std::min(1.0, static_cast<double>(t.empty_space->violations) / allowed);
}

bool plausible_alternative(const Match& candidate, const SelectionSettings& s) {
  return !coverage_too_low(candidate.terms, s) && !empty_space_occupied(candidate.terms, s);
}

MatchConfidence assess_match(const ConfidenceInput& in, const Match& match,
                             const std::vector<const Match*>& pool) {
  MatchConfidence c;
  const std::vector<Eigen::Vector3f> points = thinned(in.coarse_landmark, kMaxEvidencePoints);
  c.range = (match.box.center() - in.index.T_scene_sensor().translation()).norm();
  describe_landmark(in, match, points, c);
  const double noise = measure_noise(in, match, c);
  measure_support(in, match, points, noise, c);
  c.coverage = match.terms.coverage();
  c.intrusion = empty_space_intrusion(match.terms, in.selection);
  if (in.flat_normal && in.empty_distances) {
    c.free_space_seen =
        empty_space_seen_empty(in.index, in.landmark, *in.empty_distances, match.T_scene_capture);
    c.free_space_unconfirmed = c.free_space_seen < 1.0 - in.selection.max_empty_space_violation;
  }
  // The rivals: every candidate of the search, and the poses along the match's freest motion that
  // none of them stood at.
  const std::vector<Match> probes = probe_freest_motion(in, match, c);
  std::vector<const Match*> rivals_pool = pool;
  for (const Match& p : probes) rivals_pool.push_back(&p);

  // The error is a mean over the supporting points; its spread from the noise alone falls with
  // the square root of their count. In metres the residual sigma sets its scale (scaled as the
  // error was beyond threshold_range); a noise-normalised metric's residuals are in sigma already.
  const double unit = in.metric.noise_normalised ? 1.0 : noise * match.terms.range_scale;
  c.error_sigma = unit / std::sqrt(static_cast<double>(std::max<std::size_t>(c.support, 1)));
  c.fit = match.error / unit;

  const Rivals rivals = find_rivals(in, match, rivals_pool, points);
  const auto margin = [&](const Match* rival) {
    return rival ? (rival->error - match.error) / c.error_sigma
                 : std::numeric_limits<double>::infinity();
  };
  c.local_margin = margin(rivals.local);
  c.elsewhere_margin = margin(rivals.elsewhere);
  const Match* closest = c.local_margin <= c.elsewhere_margin ? rivals.local : rivals.elsewhere;
  if (closest) c.competitor = describe_competitor(match, *closest);
  c.margin = std::min(c.local_margin, c.elsewhere_margin);

  calibrate(c, match.box, in.calibration);
  return c;
}

}  // namespace lmk::detail
