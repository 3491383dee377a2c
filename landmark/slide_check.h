// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The slide check at capture (issue #33, part 4): the directions along which a landmark's own
// points can move, or about which they can turn, while their residual stays within the sensor's
// noise. An edge slides along itself; a plane slides in itself and turns about its normal; a
// cylinder slides along and turns about its axis; a sphere turns about its centre. A search cannot
// tell the true pose from its neighbours along such a direction: on real frames the winner was
// often the truth slid 5-13 cm along the same structure. Apart from the look-alike check
// (distinctiveness.h), which looks for the landmark elsewhere in its scene.
//
// The point-to-plane residual of point p_i with normal n_i under a small motion (t, w) about the
// points' centroid c is r_i = n_i . t + ((p_i - c) x n_i) . w. Its mean square is x^T H x with
// H = mean(J_i^T J_i), J_i = [n_i, (p_i - c) x n_i / L] and x = [t, L w], L the points' RMS
// distance from c (so that a turn is measured by the distance it moves them). Along an eigenvector
// v of H with eigenvalue lambda, a motion of size s raises the RMS residual by s sqrt(lambda): it
// stays within the noise sigma up to s = sigma / sqrt(lambda) (Gelfand et al., "Geometrically
// stable sampling for the ICP algorithm", 2003, with the noise as the yardstick).

#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"

namespace lmk {

/// One way the landmark can move within the noise.
struct Slide {
  bool turn = false;  ///< a turn about `axis` through `through`; else a slide along `axis`
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();     ///< unit, capture frame
  Eigen::Vector3d through = Eigen::Vector3d::Zero();  ///< a point of a turn's axis, capture frame
  /// How far within the noise: m for a slide, rad for a turn; infinity when the points do not
  /// constrain it at all (a perfect edge, plane or cylinder).
  double extent = 0.0;
  /// How far the points move along it within the noise, m: `extent` for a slide, the turn's
  /// extent times the points' RMS distance from their centroid for a turn (s below).
  double displacement = 0.0;
};

struct SlideReport {
  std::vector<Slide> slides;  ///< the free directions, the freest first; empty: the shape fixes it
  double noise = 0.0;         ///< the residual's sigma the check measured against, m
};

/// A direction is reported when its extent within the noise exceeds this many noise sigmas (for a
/// turn, moving the points that far): a corner or a well-shaped object stays well under it, an edge
/// or a plane far over.
inline constexpr double kSlideReportSigmas = 5.0;

/// Every direction of motion of points with normals, the freest first, each with its extent within
/// `noise`: the six eigenvectors of H, or none for fewer than six points with normals. What
/// slide_check keeps the free ones of, and what a match's freedom is read from
/// (match_confidence.h).
std::vector<Slide> motion_extents(const PointCloud& points, double noise);

/// The check for points with normals (`points.normals`, unit, NaN where undefined), in a frame
/// where `noise` is the sigma of a point-to-plane residual.
SlideReport slide_check(const PointCloud& points, double noise);

/// The check for a captured landmark, against the depth noise at its capture range
/// (DepthNoise::residual_sigma at the distance from its sensor to its box).
SlideReport slide_check(const Landmark& landmark, const DepthNoise& noise = {});

/// "the box's x" when `axis` lies within 15 degrees of one of `box`'s axes, else its components
/// "(0.71, 0.71, 0.00)", in the frame of both.
std::string describe_axis(const Eigen::Vector3d& axis, const Box& box);

/// One line per free direction, in the landmark's box axes where one lies within 15 degrees:
/// "slides 9 cm along the box's x within the noise", "turns freely about the box's z", with the
/// advice to widen the box to take in an end or a corner. Empty when nothing is free.
std::vector<std::string> describe_slides(const SlideReport& report, const Box& box);

}  // namespace lmk
