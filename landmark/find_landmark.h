#pragma once
// FindLandmark: every instance of a landmark in a scene, with its 6-DoF pose.
//
// Method "fast" (the default) seeds full 6-DoF poses by point pair voting, aligns coarse to fine on
// grids, refines the finalists with Ceres and scores with the visibility-aware metric
// (detail/fast_search.h). Method "reference" is Algorithm 1 of Huang & Cakmak exactly as
// published, on PCL's ICP as the authors ran it; it is the baseline every other method is
// measured against.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry/box.h"
#include "landmark/error_metrics.h"
#include "landmark/landmark.h"
#include "landmark/scene_index.h"

namespace lmk {

struct FindSettings {
  std::string method = "fast";  ///< search method: "fast" or "reference"
  /// Error metric, by registry name (error_metrics.h). Empty: the method's own, "visibility" for
  /// fast and "paper" for reference.
  std::string metric;
  /// Step 1: crop the scene to this box (scene frame) first; nothing means the whole scene.
  std::optional<Box> work_volume;
  double leaf_size = 0.005;   ///< step 2: scene voxel leaf, m
  double coarse_leaf = 0.01;  ///< fast: leaf of the seeds, voting and coarse alignment, m
  /// Step 3 (reference): fraction of the downsampled points used as seeds.
  double sample_fraction = 0.05;
  /// Fast: as many seeds as put about this many on one instance of the landmark (the scene's coarse
  /// points over the landmark's, times this). Each seed on an instance votes for its pose, so a
  /// handful leave room for a half-occluded instance and for seeds on its edges, whose normals are
  /// poor, while a search costs a few hundred seeds rather than a thousand. 8 finds all of the
  /// rotation and real-data acceptance trials (as 12 did) at two thirds of the voting time.
  double seeds_per_instance = 8.0;
  /// Step 3: at most this many seeds. Unset: the method's own, effective_max_seeds(): the paper's
  /// 1000 for the reference; 2000 for fast, whose seeds cost little and whose seed count otherwise
  /// follows seeds_per_instance (a small landmark in a large scene wants more than 1000).
  std::optional<std::size_t> max_seeds;
  std::uint64_t seed = 0;    ///< step 3: random seed of the sampling
  int icp_iterations = 50;   ///< reference, step 4: ICP iterations per seed (PCL's ICP)
  double nms_radius = 0.03;  ///< step 5: non-max suppression radius on box centres, m
  /// Step 6: matches need an error below this, m. Unset: the metric's default threshold.
  std::optional<double> threshold;
  /// Fast: matches need at least this fraction of their points supported by the scene (only for
  /// metrics that measure coverage).
  double min_coverage = 0.5;
  /// Fast: matches may have at most this fraction of the landmark's observed-empty voxels occupied
  /// by the scene (only for metrics that test empty space). The landmark's empty space keeps a
  /// margin from its surface that absorbs depth noise and the pose error of a true match, so a true
  /// instance leaves it empty; the 1% allowance is for the Kinect's isolated flying pixels at depth
  /// edges, not for surfaces.
  double max_empty_space_violation = 0.01;

  // Orientation (fast). "upright": any rotation about the up axis, and tilts of the landmark's
  // capture up axis up to max_tilt; "full": all of SO(3).
  std::string orientations = "upright";
  double max_tilt = 1.0471975511965976;  ///< rad (60 degrees)
  /// The scene's up axis, scene frame. Unset: default_up() (the sensor's -y, or +z in a base
  /// frame).
  std::optional<Eigen::Vector3d> up;
  bool base_frame = false;  ///< the scene is expressed in a robot base frame

  // Coarse to fine (fast).
  /// Point-pair voting samples the landmark and the scene at this fraction of the landmark's
  /// diameter (at least the coarse leaf). Drost et al.'s 5% found the same poses at twice the cost.
  double vote_leaf_fraction = 0.07;
  int poses_per_seed = 3;            ///< best-voted poses kept per seed
  std::size_t max_candidates = 400;  ///< pose clusters aligned coarsely
  double prune_error = 0.015;        ///< coarse fit beyond which a candidate is dropped, m
  std::size_t max_refined = 16;      ///< candidates refined fully
  bool refine = true;                ///< Ceres robust refinement of the finalists
  bool keep_aligned_points = false;  ///< return each match's landmark points in the scene frame
  int threads = 0;                   ///< worker threads; 0 uses every core
  /// Called after each seed with (seeds done, seeds in all), possibly from several threads at once.
  std::function<void(std::size_t, std::size_t)> progress;
};

struct Match {
  /// The matched box in the scene frame: the capture box moved by T_scene_capture.
  Box box;
  /// The rigid motion taking the landmark from its capture frame into the scene.
  Eigen::Isometry3d T_scene_capture = Eigen::Isometry3d::Identity();
  double error = 0.0;
  ErrorTerms terms;
  std::size_t seed_index = 0;  ///< which seed this match came from
  Eigen::Vector3f seed_point;  ///< that seed's scene point
  int icp_iterations = 0;
  bool icp_converged = false;
  double votes = 0.0;         ///< fast: point-pair votes of the pose cluster this match came from
  PointCloud aligned_points;  ///< only with keep_aligned_points
};

struct SearchStats {
  double seconds_preprocess = 0.0;  ///< crop, downsample, indexing, seeding
  double seconds_search = 0.0;      ///< ICP and scoring of every seed
  double seconds_select = 0.0;      ///< non-max suppression and threshold
  double seconds_total = 0.0;
  std::size_t scene_points = 0;       ///< finite points in the input scene
  std::size_t scene_points_used = 0;  ///< after crop and downsampling
  std::size_t seeds = 0;
  std::size_t icp_iterations = 0;  ///< summed over seeds
  std::size_t after_nms = 0;       ///< candidates left by non-max suppression
  std::size_t poses = 0;           ///< fast: poses voted by the seeds
  std::size_t clusters = 0;        ///< fast: pose clusters aligned coarsely
  std::size_t refined = 0;         ///< fast: candidates refined fully
  double seconds_vote = 0.0;       ///< fast, part of seconds_search: voting and clustering
  double seconds_coarse = 0.0;     ///< fast, part of seconds_search: coarse alignment and pruning
  double seconds_fine = 0.0;       ///< fast, part of seconds_search: refinement and scoring
  double threshold = 0.0;          ///< the error threshold applied, m
  /// Candidates left by non-max suppression and then rejected, by the first test they failed.
  std::size_t rejected_error = 0;        ///< error at or above the threshold
  std::size_t rejected_coverage = 0;     ///< coverage below min_coverage
  std::size_t rejected_empty_space = 0;  ///< empty space occupied beyond the allowance
  std::string method;                    ///< the search method run
  std::string metric;                    ///< the metric applied
};

struct FindResult {
  std::vector<Match> matches;  ///< sorted by increasing error
  SearchStats stats;
};

/// Finds `landmark` in `scene`. Deterministic for a fixed settings.seed whatever the thread count.
/// Throws lmk::Error for bad settings (unknown method or metric, non-positive sizes) or when the
/// scene holds no finite point (after the work-volume crop).
FindResult find_landmark(const PointCloud& scene, const Landmark& landmark,
                         const FindSettings& settings = {});

/// The same in a scene indexed once (scene_settings(settings) should have built it), so that
/// several landmarks, or several threads, can share the preprocessing. The index's own settings
/// (work volume, leaves, up axis) win over those in `settings`.
FindResult find_landmark(const SceneIndex& scene, const Landmark& landmark,
                         const FindSettings& settings = {});

/// One line on what the search turned down and why, for users and logs: "" when nothing was, and
/// "no candidate pose ..." when the scene offered none.
std::string describe_rejections(const SearchStats& stats);

/// The scene settings a FindSettings implies.
SceneSettings scene_settings(const FindSettings& settings);

/// The metric a search applies: settings.metric, or the method's own when it is empty
/// ("visibility" for fast, "paper" for reference).
std::string effective_metric(const FindSettings& settings);

/// The error threshold a search applies: settings.threshold, or its metric's default.
double effective_threshold(const FindSettings& settings);

/// The seed cap a search applies: settings.max_seeds, or its method's own.
std::size_t effective_max_seeds(const FindSettings& settings);

/// The search methods find_landmark accepts.
std::vector<std::string> search_methods();

}  // namespace lmk
