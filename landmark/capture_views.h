// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A landmark demonstrated from several views (issue #35), beyond the paper's single view: "Future
// implementations could fuse multiple point clouds across time or viewpoints" (its section
// "Advantages and limitations").
//
// Each view is a frame with its pose in the capture frame, which is the first view's frame. The
// first view's points inside the box are the one-view landmark's; each further view adds the
// surfaces no earlier view measured, and every point keeps the views that measured it
// (Landmark::point_views). The free space is the union of what each view saw free, except where
// any view measured a surface (EmptySpaceGrid::observe_views). Searches count only the points the
// scene's sensor can see: turned towards it, inside its image and not behind the landmark's own
// nearer points, since a frame taken from the front does not show a landmark's back
// (docs/landmarks.md, "Landmarks from several views").

#include <functional>
#include <vector>

#include "lmk/landmark/landmark.h"
#include "lmk/registration/frame_registration.h"

namespace lmk {

/// One view of a landmark: a frame (in its own frame, with its sensor pose) and the pose of that
/// frame in the capture frame.
struct CaptureView {
  const PointCloud* cloud = nullptr;
  Eigen::Isometry3d T_capture_cloud = Eigen::Isometry3d::Identity();
};

/// Cuts one landmark out of 1 to kMaxLandmarkViews views with one box (in the capture frame). One
/// view at the identity is capture() exactly. Throws lmk::Error as capture() does, and for a view
/// without a cloud, with a pose that is not a finite rigid motion, or with no point inside the box.
Landmark capture_views(const std::vector<CaptureView>& views, const Box& box,
                       const std::string& name, const CaptureSettings& settings = {});

/// When a registration joins a view to the first well enough to fuse it.
/// Two stages: the coarse one reaches the basin from a guess some centimetres and degrees off; the
/// fine one, with correspondences within 1.5 cm, is not pulled aside by the surfaces only one of
/// the views saw (on a tabletop seen from the front and the side, the coarse stage alone settled
/// 0.7 degrees off the exact pose it started from; the fine one 0.1).
struct ViewRegistrationSettings {
  FrameRegistrationSettings coarse;  ///< 2 cm voxels, 5 cm, Huber 1 cm
  /// 1 cm voxels, 1.5 cm, Huber 5 mm.
  FrameRegistrationSettings fine{0.01, {0.015, {RobustKernel::huber, 0.005}}, {60}};
  /// The least share of the view's fine points that must find the first view's surface within
  /// fine.correspondences.max_distance: less, and the two frames do not see the same place. A
  /// camera panning across a kitchen at 2 m keeps 23% of its frame on the first after 25 degrees
  /// (7-Scenes frames 150 and 195), with residuals no worse than at 3 degrees.
  double min_overlap = 0.2;
  /// The largest mean residual of those points, m: more, and the surfaces do not agree. Residuals
  /// spread evenly up to fine.correspondences.max_distance average 7.5 mm; registered kitchen
  /// frames at 2 m gave 3.8-5.0 mm.
  double max_residual = 0.007;
};

/// A view joined to the first by registration.
struct ViewRegistration {
  Eigen::Isometry3d T_first_view = Eigen::Isometry3d::Identity();
  double residual = 0.0;  ///< mean residual of the overlapping points, m
  double overlap = 0.0;   ///< share of the view's reduced points that overlap the first view
  int iterations = 0;
  bool converged = false;
  /// How far the registration moved the view from its guess, at the box's centre (m) and in
  /// rotation (rad).
  double moved = 0.0, turned = 0.0;
};

/// Registers `view` (its own frame) onto `first` from `guess` (T_first_view: the identity when
/// both clouds are in one frame, as a robot's base-frame clouds are; from poses otherwise). Throws
/// lmk::Error naming the view (`view_number`, from 1), its overlap and residual, when the overlap
/// is below settings.min_overlap or the residual above settings.max_residual: those, not ICP's
/// last step, say whether the two frames agree.
ViewRegistration register_view(const PointCloud& first, const PointCloud& view,
                               const Eigen::Isometry3d& guess, const Box& box,
                               std::size_t view_number,
                               const ViewRegistrationSettings& settings = {});

/// How the views of a capture are placed in the first view's frame (place_views()).
struct ViewPlacement {
  /// Each view's cloud frame in one common frame, the first view's included (a bag's TF, an RGB-D
  /// sequence's poses); empty: the clouds share one frame, as a robot's base-frame clouds do.
  std::vector<Eigen::Isometry3d> poses;
  /// Refine the poses by registration onto the first view. Without poses the views are always
  /// registered, from the identity.
  bool register_views = false;
  ViewRegistrationSettings registration;
};

/// Where each of `clouds` (at least one; the first is the capture frame) lies in the first's frame:
/// from the poses when given, by registration onto the first view when not or when asked to
/// refine them. `on_registered` hears of each registration with its view number (from 2). Throws
/// lmk::Error for a pose count that is not one per cloud, and as register_view() does. What `lmk
/// capture`, `lmk serve` and lmk_node all call, so that each reaches the same landmark.
std::vector<CaptureView> place_views(
    const std::vector<const PointCloud*>& clouds, const Box& box, const ViewPlacement& placement,
    const std::function<void(std::size_t, const ViewRegistration&)>& on_registered = {});

}  // namespace lmk
