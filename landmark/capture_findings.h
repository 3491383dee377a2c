// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the capture check knew about a landmark (issue #59): the noise of the frame it was cut
// from, how far its shape lets it slide within that noise, which axes it is symmetric about, and
// whether its own scene holds a look-alike. Stored in the .lmk (format 4), carried into every
// match's confidence (MatchConfidence::capture) as a prior, and named at a program's record and
// plan when it warned (pbd). The look-alike check needs the capture scene: a file written before
// format 4 gains the rest on load (check_capture()); its look-alikes stay unknown.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace lmk {

struct CaptureFindings {
  /// Whether the findings were measured at all: false for a landmark built by hand in code (no
  /// prior, as before format 4).
  bool present = false;
  /// The capture frame's axial depth noise at the box (geometry/frame_noise.h), m; NaN where the
  /// frame did not measure it (an unorganised cloud, a file from before format 4), and the sensor
  /// model stands in.
  double noise = std::numeric_limits<double>::quiet_NaN();
  /// The slide check (slide_check.h) against that noise: the farthest the landmark's points move
  /// within it along or about a direction that is no symmetry, m; 0 when the shape fixes every such
  /// direction within kSlideReportSigmas of the noise. +infinity: free (an edge, a plane).
  double slide = 0.0;
  /// The direction of that slide or turn, capture frame (zero when `slide` is 0), and whether it
  /// is a turn.
  Eigen::Vector3d slide_axis = Eigen::Vector3d::Zero();
  bool slide_turn = false;
  /// Axes about which the landmark turns a radian (57 degrees) or more within the noise (an axis of
  /// revolution: a bowl, a bottle; three for a ball), capture frame, through `symmetry_centre`.
  /// Turns about them are the same landmark: the evaluation counts a pose that differs only by them
  /// as right.
  std::vector<Eigen::Vector3d> symmetry_axes;
  Eigen::Vector3d symmetry_centre = Eigen::Vector3d::Zero();
  /// The look-alike check (distinctiveness.h) in the capture scene; the rest is unknown without it.
  bool look_alike_checked = false;
  bool found_itself = true;     ///< the search found the captured instance itself
  std::size_t look_alikes = 0;  ///< other places in the capture scene that match
  /// The best look-alike's error over the captured instance's (>= about 1; +infinity: none).
  double look_alike_ratio = std::numeric_limits<double>::infinity();

  /// Whether the capture warned about this landmark: a slide or a turn that is no symmetry, a
  /// look-alike, or the search not finding the captured instance. (A turn about a symmetry axis
  /// is described at capture but is no doubt: every turn about it is the same landmark.)
  bool warned() const;
  /// One line per warning ("slides 9 cm along (0.00, 1.00, 0.00) within the noise", "matches 2
  /// other places in its capture scene"); empty when none.
  std::vector<std::string> warnings() const;
};

}  // namespace lmk
