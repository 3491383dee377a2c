// SPDX-License-Identifier: BSD-3-Clause
// The registration that joins a landmark's views when no pose is given (capture_views.h).
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/capture_views.h"

namespace lmk {
namespace {

// A share as a whole percentage and a length in millimetres to one decimal, for messages.
std::string percent(double share) { return std::to_string(std::lround(100.0 * share)) + "%"; }

std::string millimetres(double metres) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << 1000.0 * metres << " mm";
  return s.str();
}

}  // namespace

ViewRegistration register_view(const PointCloud& first, const PointCloud& view,
                               const Eigen::Isometry3d& guess, const Box& box,
                               std::size_t view_number, const ViewRegistrationSettings& settings) {
  const std::string what = "view " + std::to_string(view_number);
  if (!is_valid_pose(guess)) throw Error(what + ": the pose guess is not a finite rigid motion");
  if (view.count_finite() == 0 || first.count_finite() == 0) {
    throw Error(what + ": a frame without a finite point");
  }
  const IcpResult coarse =
      register_frames(reduce_for_registration(view, settings.coarse),
                      reduce_for_registration(first, settings.coarse), guess, settings.coarse);
  const PointCloud source = reduce_for_registration(view, settings.fine);
  const IcpResult r = register_frames(source, reduce_for_registration(first, settings.fine),
                                      coarse.T_target_source, settings.fine);
  ViewRegistration out;
  out.T_first_view = r.T_target_source;
  out.iterations = r.iterations;
  out.converged = r.converged;
  out.overlap = static_cast<double>(r.inliers) / static_cast<double>(source.size());
  out.residual = r.final_error;
  // Where the guess put the box's centre against where the registration does, both in the view's
  // frame mapped into the first's.
  const Eigen::Vector3d centre_in_view = guess.inverse() * box.center();
  out.moved = (out.T_first_view * centre_in_view - box.center()).norm();
  out.turned = rotation_angle_between(out.T_first_view.linear(), guess.linear());
  const std::string measured =
      "overlap " + percent(out.overlap) + ", residual " + millimetres(out.residual);
  if (out.overlap < settings.min_overlap) {
    throw Error(what + ": does not overlap the first view enough to be registered (" + measured +
                "; at least " + percent(settings.min_overlap) +
                " needed); give the views' poses, or take it nearer the first view");
  }
  if (!(out.residual <= settings.max_residual)) {
    throw Error(what + ": its surfaces disagree with the first view's after registration (" +
                measured + "; at most " + millimetres(settings.max_residual) +
                " accepted); give the views' poses");
  }
  return out;
}

std::vector<CaptureView> place_views(
    const std::vector<const PointCloud*>& clouds, const Box& box, const ViewPlacement& placement,
    const std::function<void(std::size_t, const ViewRegistration&)>& on_registered) {
  if (clouds.empty()) throw Error("capture: no view");
  const bool posed = !placement.poses.empty();
  if (posed && placement.poses.size() != clouds.size()) {
    throw Error("capture: " + std::to_string(placement.poses.size()) + " poses for " +
                std::to_string(clouds.size()) + " views; give one pose per view, in order");
  }
  std::vector<CaptureView> views{{clouds[0], Eigen::Isometry3d::Identity()}};
  for (std::size_t v = 1; v < clouds.size(); ++v) {
    const Eigen::Isometry3d guess =
        posed ? Eigen::Isometry3d(placement.poses[0].inverse() * placement.poses[v])
              : Eigen::Isometry3d::Identity();
    if (posed && !placement.register_views) {
      views.push_back({clouds[v], guess});
      continue;
    }
    const ViewRegistration r =
        register_view(*clouds[0], *clouds[v], guess, box, v + 1, placement.registration);
    if (on_registered) on_registered(v + 1, r);
    views.push_back({clouds[v], r.T_first_view});
  }
  return views;
}

}  // namespace lmk
