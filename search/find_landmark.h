// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// FindLandmark: every instance of a landmark in a scene, with its 6-DoF pose.
//
// Method "fast" (the default) seeds full 6-DoF poses by point pair voting, aligns coarse to fine on
// grids, refines the finalists with Ceres and scores with the visibility-aware metric
// (search/fast/fast_search.h). Method "reference" is Algorithm 1 of Huang & Cakmak exactly as
// published, on PCL's ICP as the authors ran it; it is the baseline every other method is
// measured against.

#include "lmk/landmark/landmark.h"
#include "lmk/search/find_result.h"
#include "lmk/search/find_settings.h"
#include "lmk/search/landmark_index.h"
#include "lmk/search/scene_index.h"

namespace lmk {

/// Bumped whenever a search's results change for the same settings and inputs (how seeds are
/// drawn, how candidates are scored), so that cached evaluations are searched again. What each
/// revision changed: docs/evaluation.md, "Search revisions".
inline constexpr int kSearchRevision = 8;

/// Finds `landmark` in `scene`. Deterministic for a fixed settings.sampling.seed whatever the
/// thread count.
/// Throws lmk::Error for bad settings (unknown method or metric, non-positive sizes) or when the
/// scene holds no finite point (after the work-volume crop).
FindResult find_landmark(const PointCloud& scene, const Landmark& landmark,
                         const FindSettings& settings = {});

/// The same in a scene indexed once (settings.scene should have built it), so that several
/// landmarks, or several threads, can share the preprocessing. The index's own settings (work
/// volume, leaves, up axis) win over settings.scene.
FindResult find_landmark(const SceneIndex& scene, const Landmark& landmark,
                         const FindSettings& settings = {});

/// The same with the landmark's own work done once (LandmarkIndex), for a landmark searched in
/// many scenes or frames: what an evaluation and a robot do. Throws lmk::Error when the index was
/// built for another method, coarse leaf or vote leaf fraction (LandmarkIndex::suits()).
FindResult find_landmark(const SceneIndex& scene, const LandmarkIndex& landmark,
                         const FindSettings& settings = {});

/// The pose T_scene_capture as the fast search would leave it had a candidate started there: its
/// fine alignment (ICP against the scene's distance field) and its Ceres polish, scored by the
/// settings' metric (FindSettings::resolved()). Not selected: the match's error and terms say how
/// it would fare. What `lmk eval --explain` measures at the true pose, beside the match that won.
/// Throws lmk::Error as find_landmark does for bad settings or an index built for others.
Match score_pose(const SceneIndex& scene, const LandmarkIndex& landmark,
                 const FindSettings& settings, const Eigen::Isometry3d& T_scene_capture);

/// The landmark looked for only near `T_predicted` (T_scene_capture, as a tracker predicts it from
/// the frames before): score_pose's fine alignment and polish from there, then the search's own
/// selection (threshold, coverage, empty space, colour, what the view fixes) and confidence. At
/// most one match; a candidate turned down is in `rejected` with its reason. A few milliseconds
/// where a search takes tens: what `Tracker` runs on every frame.
FindResult find_near_pose(const SceneIndex& scene, const LandmarkIndex& landmark,
                          const FindSettings& settings, const Eigen::Isometry3d& T_predicted);

}  // namespace lmk
