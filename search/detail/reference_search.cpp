// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/detail/reference_search.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "lmk/geometry/filters.h"
#include "lmk/geometry/voxel_grid.h"

namespace lmk::detail {
namespace {

using PclCloud = pcl::PointCloud<pcl::PointXYZ>;

PclCloud::Ptr to_pcl_xyz(const PointCloud& cloud) {
  auto out = std::make_shared<PclCloud>();
  out->reserve(cloud.size());
  for (const auto& p : cloud.points) out->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return out;
}

// PCL keeps the iteration count protected; this exposes it for the search statistics.
class CountingIcp : public pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> {
 public:
  int iterations() const { return nr_iterations_; }
};

// One ICP per worker thread. PCL builds the target k-d tree at the first align() and reuses it
// while the target is unchanged, so each worker indexes the scene once rather than once per seed as
// the authors' code did. The alignment itself is unchanged.
struct Worker {
  Worker(const PclCloud::Ptr& scene, const PclCloud::Ptr& source, int iterations) {
    icp.setInputTarget(scene);
    icp.setInputSource(source);
    icp.setMaximumIterations(iterations);
  }
  CountingIcp icp;
  PclCloud aligned;
};

// The landmark aligned by ICP from `guess` and scored (Algorithm 1, lines 6-8), into `m`.
void align_from(const SearchInput& in, Worker& w, const Eigen::Isometry3d& guess, Match& m) {
  w.icp.align(w.aligned, guess.matrix().cast<float>());
  m.T_scene_capture.matrix() = w.icp.getFinalTransformation().cast<double>();
  // PCL composes float increments; re-orthonormalise so the pose is a proper rotation.
  m.T_scene_capture.linear() =
      Eigen::Quaterniond(m.T_scene_capture.linear()).normalized().toRotationMatrix();
  m.icp_iterations = w.icp.iterations();
  m.icp_converged = w.icp.hasConverged();
  m.terms = in.metric.evaluate(in.scene_view, in.landmark_view, m.T_scene_capture);
  m.error = m.terms.error;
  m.box = in.landmark.box.transformed(m.T_scene_capture);
}

// One candidate per seed, in seed order (Algorithm 1, lines 4-8).
std::vector<Match> reference_candidates(const SearchInput& in) {
  const PclCloud::Ptr scene = to_pcl_xyz(in.scene);
  const PclCloud::Ptr source = to_pcl_xyz(in.landmark.points);
  const Eigen::Vector3d centroid = [&] {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& p : in.landmark.points.points) sum += p.cast<double>();
    return (sum / static_cast<double>(in.landmark.points.size())).eval();
  }();

  tbb::enumerable_thread_specific<Worker> workers(scene, source,
                                                  in.settings.reference.icp_iterations);
  std::vector<Match> candidates(in.seeds.size());
  std::atomic<std::size_t> done{0};

  tbb::parallel_for(std::size_t{0}, in.seeds.size(), [&](std::size_t s) {
    if (in.settings.execution.stop) in.settings.execution.stop();
    Worker& w = workers.local();
    Match& m = candidates[s];
    m.seed_index = s;
    m.seed_point = in.scene.points[in.seeds[s]];
    // Centre the landmark on the seed, keeping the capture orientation (Algorithm 1, line 6).
    Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
    guess.translation() = m.seed_point.cast<double>() - centroid;
    align_from(in, w, guess, m);
    if (in.settings.execution.progress) in.settings.execution.progress(++done, in.seeds.size());
  });
  return candidates;
}

// The reference derives nothing from a landmark alone: every index suits it.
class NoLandmarkWork final : public MethodLandmark {
 public:
  bool suits(const FindSettings&) const override { return true; }
  std::string built_for() const override { return ""; }
};

class ReferenceSearch final : public SearchMethodSteps {
 public:
  // The paper's 1000 seeds at most, and its metric.
  std::size_t default_max_seeds() const override { return 1000; }
  const char* default_metric() const override { return "paper"; }

  std::unique_ptr<const MethodLandmark> prepare(const Landmark&,
                                                const FindSettings&) const override {
    return std::make_unique<NoLandmarkWork>();
  }
  std::string prepared_for(const FindSettings&) const override { return ""; }

  const PointCloud& seed_cloud(const SceneIndex& index) const override { return index.fine(); }

  // Step 3: a seeded random sample of sample_fraction of the points, at most max_seeds.
  Indices seeds(const SceneIndex& index, const LandmarkIndex&,
                const FindSettings& settings) const override {
    const std::size_t n = seed_cloud(index).size();
    const auto wanted = static_cast<std::size_t>(
        std::ceil(settings.reference.sample_fraction * static_cast<double>(n)));
    return random_sample_indices(n, std::min(*settings.sampling.max_seeds, wanted),
                                 settings.sampling.seed);
  }

  CandidateSet candidates(const SearchInput& input, SearchStats&) const override {
    return {reference_candidates(input), {}};
  }

  // Lines 6-8 from the given pose: PCL's ICP as for a seed, then the score.
  Match align_at(const SearchInput& input,
                 const Eigen::Isometry3d& T_scene_capture) const override {
    Worker w(to_pcl_xyz(input.scene), to_pcl_xyz(input.landmark.points),
             input.settings.reference.icp_iterations);
    Match m;
    align_from(input, w, T_scene_capture, m);
    return m;
  }

  // The reference keeps no coarse landmark: the competitor check's is made here.
  const PointCloud& coarse_landmark(const LandmarkIndex& prepared, const SceneIndex& index,
                                    PointCloud& storage) const override {
    storage = voxel_downsample(prepared.landmark().points, index.settings().coarse_leaf);
    return storage;
  }

  bool suppresses_overlaps(const FindSettings&) const override { return false; }
};

}  // namespace

const SearchMethodSteps& reference_search_steps() {
  static const ReferenceSearch steps;
  return steps;
}

}  // namespace lmk::detail
