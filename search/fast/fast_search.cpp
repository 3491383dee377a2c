// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/fast/fast_search.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "lmk/geometry/internal/voxel_key.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/radius_grid.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/registration/icp.h"
#include "lmk/registration/refine_pose.h"
#include "lmk/search/fast/coarse_fit.h"
#include "lmk/search/fast/fast_landmark.h"
#include "lmk/search/fast/point_pair_voting.h"
#include "lmk/search/fast/relief_seeds.h"
#include "lmk/search/fast/thinning.h"
#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/search/metrics/sensor_metric.h"
#include "lmk/search/non_max_suppression.h"

namespace lmk::detail {
namespace {

struct Candidate {
  Eigen::Isometry3d T_scene_capture;
  Eigen::Vector3d centre;  ///< the landmark box centre under the pose
  double votes = 0.0;
  std::size_t seed = 0;
};

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

// What the stages share: the search's input, the scene's coarse points and leaf, and the tilt
// limit of an upright search (none when every orientation is searched).
struct Stages {
  explicit Stages(const SearchInput& input)
      : in(input),
        s(input.settings),
        landmark(input.landmark),
        index(input.index),
        model(fast_landmark(input.prepared)),
        coarse(input.index.coarse()),
        leaf(input.index.settings().coarse_leaf) {
    tilt.model_up = landmark.up.cast<float>();
    tilt.scene_up = index.up().cast<float>();
    tilt.min_cos = static_cast<float>(std::cos(s.fast.max_tilt));
    limit = s.fast.orientations == Orientations::upright ? &tilt : nullptr;
  }
  Stages(const Stages&) = delete;
  Stages& operator=(const Stages&) = delete;

  const SearchInput& in;
  const FindSettings& s;
  const Landmark& landmark;
  const SceneIndex& index;
  const FastLandmark& model;  ///< the landmark's coarse points and point pair model
  const PointCloud& coarse;
  const double leaf;
  TiltLimit tilt;
  const TiltLimit* limit = nullptr;
};

// Step 1's scene: the coarse points at the voting resolution, as the landmark's model reached it
// (LandmarkIndex), bucketed for the seeds' neighbourhoods (one radius, the diameter, for every
// seed). Built beside the seeds (SearchMethodSteps::prepare_scene).
class VotingScene final : public MethodScene {
 public:
  VotingScene(const PointCloud& coarse, double coarse_leaf, const FastLandmark& model)
      : downsampled_(model.vote_leaf() > coarse_leaf * 1.01
                         ? std::optional<PointCloud>(voxel_downsample(coarse, model.vote_leaf()))
                         : std::nullopt),
        voters_(downsampled_ ? *downsampled_ : coarse),
        grid_(voters_, 0.5 * model.diameter()) {}

  const PointCloud& voters() const { return voters_; }
  const RadiusGrid& grid() const { return grid_; }

 private:
  std::optional<PointCloud> downsampled_;  ///< none: the coarse points are already at the leaf
  const PointCloud& voters_;
  RadiusGrid grid_;
};

// Step 1: poses from every seed, in parallel, each into its own slot. Upright searches vote only
// for poses within the tilt limit.
std::vector<Candidate> vote(const Stages& st) {
  const SearchInput& in = st.in;
  const double vote_leaf = st.model.vote_leaf();
  std::optional<VotingScene> own;
  const auto* given = dynamic_cast<const VotingScene*>(in.method_scene);
  if (!given) own.emplace(st.coarse, st.leaf, st.model);
  const VotingScene& scene = given ? *given : *own;
  const PointCloud& voters = scene.voters();
  const RadiusGrid& voter_grid = scene.grid();
  // Each seed votes at the voting point nearest to it: the centroid of its own voting voxel, no
  // farther than that voxel's diagonal, is a candidate.
  const auto reach = static_cast<float>(1.01 * std::sqrt(3.0) * vote_leaf);
  std::vector<Index> references(in.seeds.size());
  for (std::size_t k = 0; k < in.seeds.size(); ++k) {
    const auto n = voter_grid.nearest_within(st.coarse.points[in.seeds[k]], reach);
    references[k] = n ? n->index : 0;
  }
  const PointPairModel& pairs = st.model.point_pairs();
  const auto& progress = st.s.execution.progress;
  std::vector<std::vector<PoseVote>> votes(in.seeds.size());
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(std::size_t{0}, in.seeds.size(), [&](std::size_t k) {
    if (st.s.execution.stop) st.s.execution.stop();  // each item: a few ms at most
    pairs.vote(voters, voter_grid, references[k], st.s.fast.poses_per_seed, 0.75, votes[k],
               st.limit);
    if (progress) progress(++done, in.seeds.size());
  });
  std::vector<Candidate> poses;
  for (std::size_t k = 0; k < votes.size(); ++k) {
    for (const PoseVote& v : votes[k]) {
      poses.push_back({v.T_scene_model, v.T_scene_model * st.landmark.box.center(), v.votes, k});
    }
  }
  return poses;
}

// The cheap score beyond which a coarsely aligned candidate goes no further (infinite for a metric
// without a cheap score: every candidate ranks as voted).
double prune_bound(const Stages& st) {
  return st.in.metric.coarse_score ? st.s.fast.prune_scale * st.in.metric.prune_bound()
                                   : std::numeric_limits<double>::infinity();
}

// Step 3, first half: every cluster aligned coarsely and scored cheaply, in parallel.
struct CoarseAlignment {
  std::vector<Eigen::Isometry3d> aligned;  ///< per cluster
  std::vector<int> iterations;             ///< ICP iterations per cluster
  std::vector<double> quick;               ///< the metric's coarse score (0 without one)
};

CoarseAlignment coarse_align(const Stages& st, const std::vector<Candidate>& clusters) {
  const SearchInput& in = st.in;
  IcpSettings icp_settings;
  icp_settings.termination.max_iterations = 8;
  icp_settings.correspondences = {st.index.field().band(), {RobustKernel::huber, st.leaf}};
  // A coarse pose only has to reach the fine alignment's basin: a step under a tenth of a leaf
  // and half a degree ends it (the fine alignment keeps its own, tight tolerances).
  icp_settings.termination.translation_tolerance = 0.1 * st.leaf;
  icp_settings.termination.rotation_tolerance = 0.01;
  icp_settings.measure_final = false;  // the metric's coarse score ranks the candidates
  // A few hundred points fix a coarse pose as well as all of them, and score it as well: the
  // candidates are many, and the score only ranks them for the fine stage, which scores the
  // finalists with every point.
  const PointCloud& model = st.model.coarse();
  const PointCloud coarse_model = model.select(thin_indices(model.size(), 400));
  // The metric's own cheap score over `points`, in its unit (none: every candidate ranks as
  // voted). The score keeps a pointer to `points`.
  const auto cheap_score = [&](const PointCloud& points) -> CoarseScore {
    if (!in.metric.coarse_score) return {};
    return in.metric.coarse_score(
        {st.index, st.landmark, model, points,
         in.metric.needs_empty_distances ? &in.prepared.empty_distances() : nullptr, st.leaf});
  };
  const CoarseScore quick = cheap_score(coarse_model);
  // Most clusters of a cluttered frame are votes for a wrong place, and take all their ICP steps to
  // a score the prune drops: a few steps and a cheaper score tell most of them (coarse_fit.h).
  const PointCloud test_model = model.select(thin_indices(model.size(), kStopTestPoints));
  const CoarseScore test = cheap_score(test_model);
  const double hopeless_above = kHopelessMargin * prune_bound(st);
  CoarseAlignment out;
  out.aligned.resize(clusters.size());
  out.iterations.assign(clusters.size(), 0);
  out.quick.resize(clusters.size());
  tbb::parallel_for(std::size_t{0}, clusters.size(), [&](std::size_t c) {
    if (st.s.execution.stop) st.s.execution.stop();  // each item: a few ms at most
    const DistanceFieldTarget target(st.index.field(), &st.coarse.normals);
    const CoarseFit fit = coarse_fit(coarse_model.points, target, clusters[c].T_scene_capture,
                                     icp_settings, quick, test, hopeless_above);
    out.aligned[c] = fit.pose;
    out.iterations[c] = fit.iterations;
    out.quick[c] = fit.score;
  });
  return out;
}

// Step 3, second half: only candidates whose coarse fit could still pass go on, best first, at
// most max_refined, one per pose; returned in cluster rank, a deterministic order.
std::vector<std::size_t> prune(const Stages& st, const CoarseAlignment& coarse) {
  const double prune_at = prune_bound(st);
  const std::vector<double>& quick = coarse.quick;
  const std::vector<Eigen::Isometry3d>& aligned = coarse.aligned;
  std::vector<std::size_t> order(quick.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return quick[a] < quick[b]; });
  const Eigen::Vector3d centre = st.landmark.box.center();
  const auto same_pose = [&](std::size_t a, std::size_t b) {
    return (aligned[a] * centre - aligned[b] * centre).norm() < st.leaf &&
           rotation_angle_between(aligned[a].linear(), aligned[b].linear()) < 0.2;
  };
  std::vector<std::size_t> survivors;
  for (std::size_t c : order) {
    if (quick[c] > prune_at || survivors.size() >= st.s.fast.max_refined) continue;
    if (!within_tilt(st.limit, aligned[c])) continue;
    if (std::none_of(survivors.begin(), survivors.end(),
                     [&](std::size_t kept) { return same_pose(kept, c); })) {
      survivors.push_back(c);
    }
  }
  std::sort(survivors.begin(), survivors.end());
  return survivors;
}

// Step 4's alignment of one candidate: ICP on up to 1000 landmark points from `start`, scored by
// the metric.
struct FineAlignment {
  explicit FineAlignment(const Stages& st) : points(thin(st.landmark.points.points, 1000)) {
    icp_settings.termination.max_iterations = 10;  // the default, tight tolerances otherwise
    icp_settings.correspondences = {0.5 * st.index.field().band(),
                                    {RobustKernel::huber, 0.5 * st.leaf}};
    icp_settings.measure_final = false;  // the metric scores the result
  }

  Match align(const Stages& st, const Eigen::Isometry3d& start) const {
    const DistanceFieldTarget target(st.index.field(), &st.coarse.normals);
    const IcpResult r = icp(points, target, start, icp_settings);
    Match m;
    m.T_scene_capture = r.T_target_source;
    m.terms = st.in.metric.evaluate(st.in.scene_view, st.in.landmark_view, m.T_scene_capture);
    m.icp_iterations = r.iterations;
    m.icp_converged = r.converged;
    m.error = m.terms.error;
    m.box = st.landmark.box.transformed(m.T_scene_capture);
    return m;
  }

  IcpSettings icp_settings;
  std::vector<Eigen::Vector3f> points;
};

// Step 4: the survivors aligned finely and scored, in parallel; those the alignment tilted beyond
// the limit are dropped before they can suppress an upright one.
std::vector<Match> fine_align(const Stages& st, const std::vector<Candidate>& clusters,
                              const CoarseAlignment& coarse,
                              const std::vector<std::size_t>& survivors) {
  const FineAlignment fine(st);
  std::vector<Match> matches(survivors.size());
  tbb::parallel_for(std::size_t{0}, survivors.size(), [&](std::size_t k) {
    if (st.s.execution.stop) st.s.execution.stop();  // each item: a few ms at most
    const std::size_t c = survivors[k];
    Match& m = matches[k];
    m = fine.align(st, coarse.aligned[c]);
    m.icp_iterations += coarse.iterations[c];
    m.seed_index = clusters[c].seed;
    m.seed_point = st.coarse.points[st.in.seeds[clusters[c].seed]];
    m.votes = clusters[c].votes;
  });
  matches.erase(
      std::remove_if(matches.begin(), matches.end(),
                     [&](const Match& m) { return !within_tilt(st.limit, m.T_scene_capture); }),
      matches.end());
  return matches;
}

// Step 5's refinement of one candidate: Ceres with the empty-space penalty, kept when it scores no
// worse.
struct Polish {
  explicit Polish(const Stages& st)
      : points(thin(st.landmark.points.points, 400)),
        empty_probes(thin(st.landmark.empty_space.centres(), 300)) {
    refine.empty_space_weight = 1.0;
    refine.empty_space_margin = st.index.settings().leaf_size;
  }

  void apply(const Stages& st, Match& m) const {
    const Eigen::Isometry3d polished =
        refine_pose(points, st.index.field(), m.T_scene_capture, refine, empty_probes)
            .T_target_source;
    ErrorTerms terms = st.in.metric.evaluate(st.in.scene_view, st.in.landmark_view, polished);
    if (terms.error <= m.terms.error) {
      m.T_scene_capture = polished;
      m.terms = terms;
      m.error = terms.error;
      m.box = st.landmark.box.transformed(polished);
    }
  }

  std::vector<Eigen::Vector3f> points, empty_probes;
  RefineSettings refine;
};

// Step 5, early: of candidates within the suppression radius of each other only the best survives
// selection, so only it is worth Ceres' time. The winners within half again of the threshold are
// polished. The suppressed go to `suppressed`: rivals of the matches' confidence.
std::vector<Match> polish(const Stages& st, std::vector<Match> aligned,
                          std::vector<Match>& suppressed) {
  std::vector<std::size_t> kept = non_max_suppression_of(aligned, st.s.selection.nms_radius);
  std::sort(kept.begin(), kept.end());  // cluster rank again: a deterministic order
  std::vector<Match> matches;
  std::vector<char> is_kept(aligned.size(), 0);
  for (std::size_t k : kept) is_kept[k] = 1;
  for (std::size_t k = 0; k < aligned.size(); ++k) {
    if (is_kept[k]) {
      matches.push_back(std::move(aligned[k]));
    } else {
      suppressed.push_back(std::move(aligned[k]));
    }
  }
  if (!st.s.fast.refine) return matches;
  const Polish refiner(st);
  // Further out than half again the threshold, a few millimetres of polish cannot make a match.
  const double worth_refining = 1.5 * st.in.threshold;
  tbb::parallel_for(std::size_t{0}, matches.size(), [&](std::size_t k) {
    if (st.s.execution.stop) st.s.execution.stop();  // each item: a few ms at most
    if (matches[k].terms.error < worth_refining) refiner.apply(st, matches[k]);
  });
  return matches;
}

// Candidates in a deterministic order (by cluster rank), whatever the thread count.
CandidateSet fast_candidates(const SearchInput& in, SearchStats& stats) {
  const Stages st(in);
  Stopwatch stage;
  std::vector<Candidate> poses = vote(st);
  stats.fast.poses = poses.size();
  // Step 2.
  const std::vector<Candidate> clusters =
      cluster(std::move(poses), std::max(2.0 * st.leaf, 0.1 * st.model.diameter()), 0.35,
              st.s.fast.max_candidates);
  stats.fast.clusters = clusters.size();
  stats.fast.seconds_vote = stage.seconds();

  stage.restart();
  const CoarseAlignment coarse = coarse_align(st, clusters);
  const std::vector<std::size_t> survivors = prune(st, coarse);
  stats.fast.refined = survivors.size();
  stats.fast.seconds_coarse = stage.seconds();

  stage.restart();
  CandidateSet out;
  out.kept = polish(st, fine_align(st, clusters, coarse, survivors), out.suppressed);
  stats.fast.seconds_fine = stage.seconds();
  return out;
}

class FastSearch final : public SearchMethodSteps {
 public:
  // 2000 seeds: they cost little, and their count otherwise follows seeds_per_instance (a small
  // landmark in a large scene wants more than the paper's 1000).
  std::size_t default_max_seeds() const override { return 2000; }
  const char* default_metric() const override { return "visibility"; }

  std::unique_ptr<const MethodLandmark> prepare(const Landmark& landmark,
                                                const FindSettings& settings) const override {
    return std::make_unique<FastLandmark>(landmark, settings);
  }
  std::string prepared_for(const FindSettings& settings) const override {
    return FastLandmark::described(settings.scene.coarse_leaf, settings.fast.vote_leaf_fraction);
  }

  const PointCloud& seed_cloud(const SceneIndex& index) const override { return index.coarse(); }

  std::unique_ptr<const MethodScene> prepare_scene(const SceneIndex& index,
                                                   const LandmarkIndex& landmark) const override {
    return std::make_unique<VotingScene>(index.coarse(), index.settings().coarse_leaf,
                                         fast_landmark(landmark));
  }

  // Step 3: seeds near relief only (relief_seeds.h), in cells of half the landmark's size, and as
  // many as put seeds_per_instance on each instance-sized stretch of them.
  Indices seeds(const SceneIndex& index, const LandmarkIndex& landmark,
                const FindSettings& settings) const override {
    const PointCloud& points = seed_cloud(index);
    const FastLandmark& model = fast_landmark(landmark);
    ReliefTest relief;
    relief.cell = 0.5 * model.diameter();
    relief.angle = kCoplanarAngle;
    relief.T_cloud_sensor = index.T_scene_sensor();
    relief.noise = index.settings().depth_noise();
    const Indices candidates = points_near_relief(points, relief);
    // One seed per cell of a grid whose cells an instance's surface (about as many coarse
    // leaves as the landmark has coarse points) spans seeds_per_instance times; coarser while the
    // seeds would exceed the cap.
    const double leaf = index.settings().coarse_leaf;
    double spacing = leaf * std::sqrt(std::max(1.0, static_cast<double>(model.coarse().size()) /
                                                        settings.fast.seeds_per_instance));
    const std::size_t cap = *settings.sampling.max_seeds;
    Indices seeds = spread_seeds(points, candidates, spacing, settings.sampling.seed);
    while (seeds.size() > cap) {
      spacing *= 1.02 * std::sqrt(static_cast<double>(seeds.size()) / static_cast<double>(cap));
      seeds = spread_seeds(points, candidates, spacing, settings.sampling.seed);
    }
    return seeds;
  }

  CandidateSet candidates(const SearchInput& input, SearchStats& stats) const override {
    return fast_candidates(input, stats);
  }

  // Stages 4 and 5 for one pose: fine alignment from it, then the Ceres polish whatever the error.
  Match align_at(const SearchInput& input,
                 const Eigen::Isometry3d& T_scene_capture) const override {
    const Stages st(input);
    Match m = FineAlignment(st).align(st, T_scene_capture);
    Polish(st).apply(st, m);
    return m;
  }

  const PointCloud& coarse_landmark(const LandmarkIndex& prepared, const SceneIndex&,
                                    PointCloud&) const override {
    return fast_landmark(prepared).coarse();
  }

  bool suppresses_overlaps(const FindSettings& settings) const override {
    return settings.fast.suppress_overlaps;
  }
};

}  // namespace

const SearchMethodSteps& fast_search_steps() {
  static const FastSearch steps;
  return steps;
}

}  // namespace lmk::detail
