// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Depth smoothing of an organised frame: each point slides along its ray to the mean depth of its
// image neighbours on the same surface.
//
// A structured-light camera rounds each depth to a level: at 2 m a Kinect v1's levels lie about
// 12 mm apart while its pixels are 4 mm apart, so a tilted surface comes as a staircase of
// terraces, and two views of it have their terraces in different places. A landmark cut from one
// view and a scene from another then disagree by up to half a level wherever they meet, and a
// point-to-surface metric cannot tell the true pose from one slid along the terraces (issue #33,
// "comparing surfaces rather than raw quantised points"). The mean over a window a few levels
// wide puts the points back on the surface, with the noise reduced; neighbours further than a few
// levels are another surface (an edge), and stay out of the mean, so edges stay sharp.

#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// The largest window radius depth smoothing takes, pixels: 10 makes a 21 x 21 window, already
/// 8 cm wide at 2 m, beyond which it would round every corner.
inline constexpr int kMaxDepthSmoothingRadius = 10;

/// The window radius captures and searches smooth with by default, pixels: none. Smoothing raises
/// recall at range on real and synthetic frames but lets look-alikes in there too (precision on
/// the synthetic `viewpoints` preset 0.947 -> 0.886 at radius 2), so it is an option for far
/// real frames, not a default (docs/evaluation.md). 2 (a 5 x 5 window, 2 cm at 2 m) is the radius
/// measured.
inline constexpr int kDefaultDepthSmoothing = 0;

/// Depth smoothing moves only points at least this far from the sensor (depth along its axis), m:
/// where a Kinect's depth levels lie 3 pixels apart or more on a surface facing it (levels
/// z^2 / (8 f b) apart, pixels z / f: z / (8 b) pixels, b = 7.5 cm), so that its terraces are wide
/// enough to be told from shape. Nearer, the levels are finer than the pixels and smoothing only
/// rounds real shape: on the synthetic `paper` preset (1-1.5 m) it cost recall
/// (docs/evaluation.md).
inline constexpr double kDepthSmoothingFrom = 1.8;

/// Neighbours whose depth differs by more than this many of the sensor's depth levels (or of its
/// axial noise, where it has no levels) are another surface.
inline constexpr double kSmoothingGateLevels = 3.0;

/// How far, m, a neighbour's depth may lie from a point's at depth z and still count as its
/// surface: kSmoothingGateLevels levels (or axial sigmas) of `noise` at z.
double depth_smoothing_gate(const DepthNoise& noise, double z);

/// Moves each finite point of an organised cloud along its ray from the sensor (T_cloud_sensor)
/// to the mean depth of the finite points in the (2 radius + 1)^2 window around its pixel that lie
/// within depth_smoothing_gate() of it. Depths are along the sensor's optical axis. An
/// unorganised cloud, or radius 0, is left as it is; NaN points stay NaN.
void smooth_depth(PointCloud& cloud, int radius, const DepthNoise& noise = {});

}  // namespace lmk
