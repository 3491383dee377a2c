// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/detail/fast_search.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "lmk/geometry/detail/voxel_key.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/radius_grid.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/landmark/detail/grid_metrics.h"
#include "lmk/landmark/detail/point_pair_voting.h"
#include "lmk/landmark/detail/sensor_metric.h"
#include "lmk/landmark/detail/stopwatch.h"
#include "lmk/landmark/non_max_suppression.h"
#include "lmk/registration/icp.h"
#include "lmk/registration/refine_pose.h"

namespace lmk::detail {
namespace {

// The coarse fit, in sigma, beyond which a candidate of the sensor metric is dropped: twice the
// metric's default threshold, as prune_error (15 mm) is for the 6 mm of `visibility`.
constexpr double kSigmaPrune = 2.0;

struct Candidate {
  Eigen::Isometry3d T_scene_capture;
  Eigen::Vector3d centre;  ///< the landmark box centre under the pose
  double votes = 0.0;
  std::size_t seed = 0;
};

// Every k-th index below n, so that at most `cap` remain (deterministic: two sets of one size keep
// the same indices).
Indices thin_indices(std::size_t n, std::size_t cap) {
  Indices out;
  const std::size_t kept = std::min(n, cap);
  const double step = static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(kept, 1));
  for (std::size_t k = 0; k < kept; ++k) out.push_back(static_cast<Index>(k * step));
  return out;
}

template <class T>
std::vector<T> thin(const std::vector<T>& items, std::size_t cap) {
  if (items.size() <= cap) return items;
  std::vector<T> out;
  for (Index i : thin_indices(items.size(), cap)) out.push_back(items[i]);
  return out;
}

// Step 2: greedy clustering, strongest pose first. A pose joins the first cluster (in order of
// creation) whose centre is within `distance` and whose rotation is within `angle`; clusters are
// ranked by summed votes. Cluster centres are binned in cells of side `distance`, so a pose looks
// at the clusters of its 27 cells only instead of at every cluster: thousands of poses met
// thousands of clusters on a room-sized frame.
std::vector<Candidate> cluster(std::vector<Candidate> poses, double distance, double angle,
                               std::size_t keep) {
  std::stable_sort(poses.begin(), poses.end(),
                   [](const Candidate& a, const Candidate& b) { return a.votes > b.votes; });
  std::vector<Candidate> clusters;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;  // cell -> clusters in it
  const double inv_cell = 1.0 / distance;
  for (const Candidate& p : poses) {
    const VoxelCoord c = voxel_coord(p.centre.cast<float>(), inv_cell);
    std::size_t first = clusters.size();
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find(pack_voxel({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == cells.end()) continue;
          for (std::size_t k : it->second) {
            if (k < first && (clusters[k].centre - p.centre).norm() < distance &&
                rotation_angle_between(clusters[k].T_scene_capture.linear(),
                                       p.T_scene_capture.linear()) < angle) {
              first = k;
            }
          }
        }
      }
    }
    if (first < clusters.size()) {
      clusters[first].votes += p.votes;
    } else {
      cells[pack_voxel(c)].push_back(clusters.size());
      clusters.push_back(p);
    }
  }
  std::stable_sort(clusters.begin(), clusters.end(),
                   [](const Candidate& a, const Candidate& b) { return a.votes > b.votes; });
  if (clusters.size() > keep) clusters.resize(keep);
  return clusters;
}

// Whether a pose keeps the landmark's up axis within the tilt limit (always, without a limit).
// Voting applies the limit to the poses it proposes; alignment can still slide a shape with a
// symmetry into a tilted pose (a chair's corner, three planes at right angles, onto a corner
// turned on its side), which an upright search has said it will not report.
bool within_tilt(const TiltLimit* limit, const Eigen::Isometry3d& T_scene_model) {
  return !limit || limit->admits(T_scene_model.linear().cast<float>());
}

}  // namespace

std::vector<Match> fast_candidates(const SearchInput& in, FastSearchStats& stats) {
  const auto start = Clock::now();
  const FindSettings& s = in.settings;
  const Landmark& landmark = in.landmark;
  const SceneIndex& index = in.index;
  const PointCloud& coarse = index.coarse();
  const double leaf = index.settings().coarse_leaf;

  const double diameter = in.prepared.diameter();
  const double vote_leaf = in.prepared.vote_leaf();
  const PointCloud& model = in.prepared.coarse();
  const PointPairModel& pairs = in.prepared.point_pairs();
  // The scene reaches the voting resolution as the landmark's model did (LandmarkIndex), and is
  // bucketed for the seeds' neighbourhoods: one radius, the diameter, for every seed.
  const bool own_vote_cloud = vote_leaf > leaf * 1.01;
  const PointCloud vote_scene = own_vote_cloud ? voxel_downsample(coarse, vote_leaf) : PointCloud();
  const PointCloud& voters = own_vote_cloud ? vote_scene : coarse;
  const RadiusGrid voter_grid(voters, 0.5 * diameter);
  // Each seed votes at the voting point nearest to it: the centroid of its own voting voxel, no
  // farther than that voxel's diagonal, is a candidate.
  const auto reach = static_cast<float>(1.01 * std::sqrt(3.0) * vote_leaf);
  std::vector<Index> references(in.seeds.size());
  for (std::size_t k = 0; k < in.seeds.size(); ++k) {
    const auto n = voter_grid.nearest_within(coarse.points[in.seeds[k]], reach);
    references[k] = n ? n->index : 0;
  }

  // Step 1: poses from every seed, in parallel, each into its own slot. Upright searches vote
  // only for poses within the tilt limit.
  TiltLimit tilt;
  tilt.model_up = landmark.up.cast<float>();
  tilt.scene_up = index.up().cast<float>();
  tilt.min_cos = static_cast<float>(std::cos(s.fast.max_tilt));
  const TiltLimit* limit = s.fast.orientations == "upright" ? &tilt : nullptr;
  std::vector<std::vector<PoseVote>> votes(in.seeds.size());
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(std::size_t{0}, in.seeds.size(), [&](std::size_t k) {
    pairs.vote(voters, voter_grid, references[k], s.fast.poses_per_seed, 0.75, votes[k], limit);
    if (s.execution.progress) s.execution.progress(++done, in.seeds.size());
  });
  std::vector<Candidate> poses;
  for (std::size_t k = 0; k < votes.size(); ++k) {
    for (const PoseVote& v : votes[k]) {
      poses.push_back({v.T_scene_model, v.T_scene_model * landmark.box.center(), v.votes, k});
    }
  }
  stats.poses = poses.size();

  // Step 2.
  const std::vector<Candidate> clusters =
      cluster(std::move(poses), std::max(2.0 * leaf, 0.1 * diameter), 0.35, s.fast.max_candidates);
  stats.clusters = clusters.size();
  stats.seconds_vote = seconds_since(start);
  const auto coarse_start = Clock::now();

  // Step 3: coarse alignment and a cheap score, in parallel.
  IcpSettings coarse_icp;
  coarse_icp.max_iterations = 8;
  coarse_icp.max_correspondence_distance = index.field().band();
  coarse_icp.loss = {RobustKernel::huber, leaf};
  // A coarse pose only has to reach the fine alignment's basin: a step under a tenth of a leaf
  // and half a degree ends it (the fine alignment keeps its own, tight tolerances).
  coarse_icp.translation_tolerance = 0.1 * leaf;
  coarse_icp.rotation_tolerance = 0.01;
  coarse_icp.measure_final = false;  // the candidates are scored below, by the metric's unit
  // A few hundred points fix a coarse pose as well as all of them, and score it as well: the
  // candidates are many, and the score only ranks them for the fine stage, which scores the
  // finalists with every point.
  const PointCloud coarse_model = model.select(thin_indices(model.size(), 400));
  std::vector<Eigen::Isometry3d> aligned(clusters.size());
  // The cheap score in the metric's unit: for the sensor metric, its own fit (sigma residuals,
  // projective visibility), so that a far instance, noisy in millimetres, still ranks first.
  const bool in_sigma = in.metric.unit == ErrorMetric::Unit::sigma;
  const Eigen::Vector3f capture_sensor = landmark.sensor_origin.cast<float>();
  const double prune = in_sigma ? kSigmaPrune : s.fast.prune_error;
  std::vector<Eigen::Vector3f> quick_probes;
  std::vector<float> quick_probe_distances;
  if (in_sigma) {
    quick_probes = thin(landmark.empty_space.centres(), 300);
    quick_probe_distances = thin(in.prepared.empty_distances(), 300);
  }
  std::vector<double> quick(clusters.size());
  std::vector<int> iterations(clusters.size(), 0);
  tbb::parallel_for(std::size_t{0}, clusters.size(), [&](std::size_t c) {
    const DistanceFieldTarget target(index.field(), &coarse.normals);
    const IcpResult r = icp(coarse_model.points, target, clusters[c].T_scene_capture, coarse_icp);
    aligned[c] = r.T_target_source;
    iterations[c] = r.iterations;
    const Eigen::Isometry3f T = aligned[c].cast<float>();
    if (in_sigma) {
      // Space the landmark needs free but the scene's sensor measured a surface in is the
      // sharpest test at range, where the fit's residuals drown in noise.
      quick[c] = sensor_fit(index, model, capture_sensor, T).mean_cost() +
                 empty_space_penalty(index, landmark, quick_probes, quick_probe_distances, T);
      return;
    }
    quick[c] = mean_surface_distance(index, coarse_model, T,
                                     in.metric.hides_occluded ? &landmark.box : nullptr);
  });

  // Prune: only candidates whose coarse fit could still pass go on, the best first.
  std::vector<std::size_t> order(clusters.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return quick[a] < quick[b]; });
  std::vector<std::size_t> survivors;
  const auto same_pose = [&](std::size_t a, std::size_t b) {
    return (aligned[a] * landmark.box.center() - aligned[b] * landmark.box.center()).norm() <
               leaf &&
           rotation_angle_between(aligned[a].linear(), aligned[b].linear()) < 0.2;
  };
  for (std::size_t c : order) {
    if (quick[c] > prune || survivors.size() >= s.fast.max_refined) continue;
    if (!within_tilt(limit, aligned[c])) continue;
    if (std::none_of(survivors.begin(), survivors.end(),
                     [&](std::size_t kept) { return same_pose(kept, c); })) {
      survivors.push_back(c);
    }
  }
  std::sort(survivors.begin(), survivors.end());  // back to cluster rank: deterministic order
  stats.refined = survivors.size();
  stats.seconds_coarse = seconds_since(coarse_start);
  const auto fine_start = Clock::now();

  // Step 4 and 5, in parallel over the survivors.
  IcpSettings fine_icp;  // the default, tight convergence tolerances
  fine_icp.max_iterations = 10;
  fine_icp.max_correspondence_distance = 0.5 * index.field().band();
  fine_icp.loss = {RobustKernel::huber, 0.5 * leaf};
  fine_icp.measure_final = false;  // the metric scores the result
  const std::vector<Eigen::Vector3f> icp_points = thin(landmark.points.points, 1000);
  const std::vector<Eigen::Vector3f> refine_points = thin(landmark.points.points, 400);
  const std::vector<Eigen::Vector3f> empty_probes = thin(landmark.empty_space.centres(), 300);
  RefineSettings refine;
  refine.empty_space_weight = 1.0;
  refine.empty_space_margin = index.settings().leaf_size;
  // Ceres polishes the finalists only: candidates whose error after ICP is within half again of
  // the threshold. Further out, a few millimetres of polish cannot make a match of them.
  const double worth_refining = 1.5 * in.threshold;
  std::vector<Match> aligned_matches(survivors.size());
  tbb::parallel_for(std::size_t{0}, survivors.size(), [&](std::size_t k) {
    const std::size_t c = survivors[k];
    const DistanceFieldTarget target(index.field(), &coarse.normals);
    const IcpResult r = icp(icp_points, target, aligned[c], fine_icp);
    Match& m = aligned_matches[k];
    m.T_scene_capture = r.T_target_source;
    m.terms = in.metric.evaluate(in.scene_view, in.landmark_view, m.T_scene_capture);
    m.icp_iterations = iterations[c] + r.iterations;
    m.icp_converged = r.converged;
    m.seed_index = clusters[c].seed;
    m.seed_point = coarse.points[in.seeds[clusters[c].seed]];
    m.votes = clusters[c].votes;
    m.error = m.terms.error;
    m.box = landmark.box.transformed(m.T_scene_capture);
  });

  // Fine alignment can tilt a candidate too: those beyond the limit go before they can suppress
  // an upright one.
  aligned_matches.erase(
      std::remove_if(aligned_matches.begin(), aligned_matches.end(),
                     [&](const Match& m) { return !within_tilt(limit, m.T_scene_capture); }),
      aligned_matches.end());

  // Step 5 comes early for the polish: of candidates within the suppression radius of each other
  // only the best survives selection, so only it is worth Ceres' time.
  std::vector<std::size_t> kept = non_max_suppression_of(aligned_matches, s.selection.nms_radius);
  std::sort(kept.begin(), kept.end());  // cluster rank again: a deterministic order
  std::vector<Match> matches;
  for (std::size_t k : kept) matches.push_back(std::move(aligned_matches[k]));
  tbb::parallel_for(std::size_t{0}, matches.size(), [&](std::size_t k) {
    Match& m = matches[k];
    if (!s.fast.refine || !(m.terms.error < worth_refining)) return;
    const Eigen::Isometry3d polished =
        refine_pose(refine_points, index.field(), m.T_scene_capture, refine, empty_probes)
            .T_target_source;
    ErrorTerms terms = in.metric.evaluate(in.scene_view, in.landmark_view, polished);
    if (terms.error <= m.terms.error) {
      m.T_scene_capture = polished;
      m.terms = terms;
      m.error = terms.error;
      m.box = landmark.box.transformed(polished);
    }
  });
  stats.seconds_fine = seconds_since(fine_start);
  return matches;
}

}  // namespace lmk::detail
