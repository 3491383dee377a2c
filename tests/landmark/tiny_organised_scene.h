// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A tiny organised scene for checking projective visibility by hand: a 40 x 30 pinhole image of a
// wall 1 m away, and a landmark of nine of its points (pixels u 18-20, v 13-15) captured from
// where the scene is seen.

#include <Eigen/Geometry>
#include <functional>
#include <string>

#include "lmk/landmark/landmark.h"
#include "lmk/landmark/scene_settings.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk {

inline constexpr int kTinyWidth = 40, kTinyHeight = 30;

/// The point at pixel (u, v) and `depth` along the optical axis.
Eigen::Vector3f on_tiny_ray(int u, int v, double depth);

/// The wall, with the depth of some pixels changed (NaN: no return); only its first `columns`
/// columns, as if the image ended there.
PointCloud tiny_wall(const std::function<double(int, int)>& depth_at, int columns = kTinyWidth);

/// Whether pixel (u, v) holds one of the landmark's nine points.
bool in_tiny_landmark(int u, int v);

/// The nine-point landmark, with the free space in front of it observed by a dense capture.
Landmark tiny_landmark();

/// `metric`'s terms for the landmark where it was captured, in `scene` indexed with `settings`.
ErrorTerms evaluate_tiny(const std::string& metric, const Landmark& landmark,
                         const PointCloud& scene, const SceneSettings& settings = {});

}  // namespace lmk
