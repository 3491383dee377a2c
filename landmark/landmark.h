// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The custom landmark of Huang & Cakmak: l = (P, B), the points a user cut out of a scene with a
// box, and the box itself. The box's empty margins say where space must stay free.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/depth_smoothing.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/landmark/capture_findings.h"
#include "lmk/landmark/scene_settings.h"
#include "lmk/occupancy/distance_field.h"
#include "lmk/occupancy/empty_space.h"

namespace lmk {

/// Version of the landmark model and of its .lmk file; bumped whenever either changes.
/// Version 2 added the up axis and the distance and empty-space grids; version 3 the views of a
/// landmark captured from several (Landmark::view_origins); version 4 what the capture check found
/// (Landmark::findings, issue #59). Versions 1 to 4 were OpenVDB files; version 5 is lmk's own
/// container, which stores what the grids are built from and rebuilds them on load (issue #61).
inline constexpr int kLandmarkFormatVersion = 5;

/// The most views one landmark fuses (Landmark::point_views holds one bit per view).
inline constexpr std::size_t kMaxLandmarkViews = 16;

/// The widest distance band a landmark may ask for, in leaves (CaptureSettings::distance_band): a
/// search reads the field a few leaves from the surface, and each leaf more of band costs a layer
/// of voxels about every point.
inline constexpr double kMaxDistanceBandLeaves = 40.0;

struct CaptureSettings {
  double leaf_size = 0.005;     ///< voxel leaf of the captured points, m (the paper's 5 mm)
  std::size_t min_points = 30;  ///< fewer points than this after downsampling is an error
  double max_box_side = 3.0;    ///< a box side longer than this is an error, m
  double distance_band = 0.02;  ///< band of the landmark's distance field, m (voxel = leaf)
  /// Observed-free space stops this far from any surface, so that depth noise is not intrusion, m.
  double empty_space_margin = 0.01;
  /// The up axis in the capture frame. Unset: default_up() of the scene.
  std::optional<Eigen::Vector3d> up;
  /// The scene is expressed in a robot base frame, whose +z is up (else the sensor's -y is).
  bool base_frame = false;
  /// Accept a flat landmark: a patch of free surface, such as the paper's empty spot on a crowded
  /// table, whose box margins say that nothing may stand on it. Its place and turn on its plane are
  /// free, so it matches wherever it fits; the programs that use one choose among the matches by
  /// a cue such as the demonstrated height. Thin straight shapes stay refused.
  bool allow_flat = false;
  /// The capture frame's veil points (geometry/veil_points.h) are dropped before the landmark is
  /// cut, rad (0 keeps them), as a search drops the scene's (SceneSettings::veil_angle): the
  /// fringe along a silhouette is the capture view's alone. Used at capture only; off by default,
  /// as SceneSettings::veil_angle.
  double veil_angle = 0.0;
  /// The capture frame's depth is smoothed over this many pixels around each point (geometry/
  /// depth_smoothing.h), as a search smooths its scene's (SceneSettings::depth_smoothing), so that
  /// a landmark and the scenes it is searched in are alike. 0: the raw depth. Used at capture only.
  int depth_smoothing = kDefaultDepthSmoothing;
  /// A structured-light sensor's projector offset along the camera's +x, m (the Kinect v1's 7.5
  /// cm): the camera's rays through the projector's shadow count as observed free up to the
  /// surface casting it (geometry/projector_shadow.h). 0 for a sensor without one (stereo, time
  /// of flight). Used at capture only: the empty space it carves is stored in the landmark.
  double projector_baseline = 0.075;

  /// Each field described once (geometry/settings_schema.h): validation, `lmk capture`'s flags and
  /// the JSON forms (a landmark's export, lmk serve) derive from this list.
  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    // As a scene's leaf: a coarser grid describes no shape of a landmark a few tens of cm across.
    visit(SettingInfo("leaf_size", "Voxel leaf of the landmark points, m (1 mm to 10 cm)")
              .within(kMinLeafSize, kMaxSceneLeaf)
              .also("leaf"),
          s.leaf_size);
    // A landmark of a million 5 mm voxels would fill a 3 m box's faces twice over.
    visit(SettingInfo("min_points", "Fewest points a landmark may have (1 to a million)")
              .within(1, 1e6),
          s.min_points);
    // A door or a shelf is a landmark; a box larger than a room holds no one object, and the
    // distance field and empty space it would allocate grow with its volume.
    visit(SettingInfo("max_box_side", "Longest allowed box side, m (at most 10)")
              .positive()
              .at_most(10.0),
          s.max_box_side);
    // At least the leaf and at most kMaxDistanceBandLeaves leaves too (check_capture_settings):
    // the field's voxels are leaves, and a search reads it no further than its threshold and a
    // few leaves (the default 2 cm). 1e308 asked for 4.7 GB, 5 m for 3 GB in 5 s, 0.5 m for 59 s
    // and a 27 MB file (issue #47).
    visit(SettingInfo("distance_band",
                      "Band of the landmark's distance field, m (at most 0.1 m and 40 leaves)")
              .positive()
              .at_most(0.1),
          s.distance_band);
    visit(SettingInfo("empty_space_margin",
                      "Observed-free space stops this far from any surface, m (at most 0.5)")
              .within(0.0, 0.5),
          s.empty_space_margin);
    visit(SettingInfo("up",
                      "Up axis X Y Z in the capture frame (default: the sensor's -y, or +z "
                      "in a robot base frame)"),
          s.up);
    visit(SettingInfo("base_frame", "The scene is expressed in a robot base frame, whose +z is up"),
          s.base_frame);
    visit(SettingInfo("allow_flat",
                      "Accept a flat landmark: a patch of free surface (an empty spot on a table), "
                      "which matches wherever it fits"),
          s.allow_flat);
    visit(
        SettingInfo("veil_angle",
                    "Drop the capture frame's veil points within this angle of the sensor's rays, "
                    "as searches do (0: keep them; keep it equal to the searches' --veil-angle)")
            .within(0.0, 1.5)
            .in_degrees(),
        s.veil_angle);
    visit(SettingInfo("depth_smoothing",
                      "Smooth an organised frame's depth over this many pixels around each point, "
                      "as searches do (0: the raw depth; keep it equal to the searches' "
                      "--depth-smoothing)")
              .within(0, kMaxDepthSmoothingRadius),
          s.depth_smoothing);
    // A projector a metre from its camera is no depth sensor lmk knows.
    visit(SettingInfo("projector_baseline",
                      "A structured-light sensor's projector offset along the camera's +x, m (0: "
                      "none, for stereo or time of flight)")
              .within(0.0, 1.0),
          s.projector_baseline);
  }
};

struct Landmark {
  std::string name;
  /// The captured points, in the capture (scene) frame, downsampled to settings.leaf_size.
  PointCloud points;
  /// The box the user drew, in the capture frame (T_capture_box at its centre).
  Box box;
  /// Where the sensor was at capture, in the capture frame: space between it and the surface was
  /// observed free.
  Eigen::Vector3d sensor_origin = Eigen::Vector3d::Zero();
  /// The up axis at capture, in the capture frame (unit). Searches limit the landmark's tilt
  /// relative to it unless they search every orientation.
  Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  /// A landmark captured from several views (capture_views(), issue #35): every view's sensor
  /// origin in the capture frame, the first being sensor_origin. Empty for one view.
  std::vector<Eigen::Vector3d> view_origins;
  /// With several views: per point, bit v set when view v measured a surface in the point's voxel.
  /// Empty for one view.
  std::vector<std::uint32_t> point_views;
  CaptureSettings settings;
  /// What the capture check found (capture_check.h): stored from format 4; a file from before
  /// gains all but the look-alike check on load.
  CaptureFindings findings;
  int format_version = kLandmarkFormatVersion;

  /// Whether the landmark fuses several views: its back may hold points that a sensor looking at
  /// its front cannot see, so searches count only the points turned towards the scene's sensor.
  bool multi_view() const { return !view_origins.empty(); }
  std::size_t view_count() const { return multi_view() ? view_origins.size() : 1; }

  // Derived from the above by prepare_landmark(); stored in the .lmk file from version 2.
  /// Distance to the landmark's points (voxel = settings.leaf_size, band = distance_band).
  DistanceField distance;
  /// The voxels of the box observed free at capture.
  EmptySpaceGrid empty_space;

  /// Throws lmk::Error naming the first field that is wrong (used after loading and importing).
  void validate(const std::string& what) const;
  /// The part of validate() about the views: 2 to kMaxLandmarkViews of them, the first at
  /// sensor_origin, and one non-empty mask of existing views per point; or none at all.
  void validate_views(const std::string& what) const;
};

/// The up axis of a cloud's frame: +z when it is a robot base frame, otherwise the -y axis of its
/// sensor (the camera convention: image rows grow downwards), expressed in the cloud's frame.
Eigen::Vector3d default_up(const Eigen::Isometry3d& T_cloud_sensor, bool base_frame);

/// The landmark points' normals (PCA of 10 neighbours, facing the capture sensor; with several
/// views, facing the first view that measured the point), into landmark.points.normals. They are
/// not stored in the file; loading recomputes them.
void estimate_landmark_normals(Landmark& landmark);

/// Computes the derived parts of a landmark: its points' normals (facing the capture sensor), its
/// distance field and its empty-space grid. Free space is observed along the rays from the
/// sensor to `scene_points` (the capture scene, capture frame); without them, only the rays to the
/// landmark's own points are known (upgrading a version-1 file, importing), which marks less space
/// as empty but never wrongly.
void prepare_landmark(Landmark& landmark,
                      const std::vector<Eigen::Vector3f>* scene_points = nullptr);

/// prepare_landmark() with each view's rays given (in the capture frame): the free space is what
/// any of them saw free (EmptySpaceGrid::observe_views).
void prepare_landmark_views(Landmark& landmark, const std::vector<RayBundle>& views);

/// Why a landmark's shape cannot fix a pose, or nothing when it can. A flat landmark (at least 95%
/// of its points within two leaves of one plane) slides and turns freely in that plane, and a thin
/// straight one (likewise around one line) turns freely about it: either would match every table
/// top or every edge in a scene. `allow_flat` accepts the flat case (CaptureSettings::allow_flat).
/// `what` names the landmark in the message.
std::optional<std::string> degenerate_shape(const PointCloud& points, double leaf_size,
                                            const std::string& what, bool allow_flat = false);

/// The normal of the plane a flat landmark's points lie on (at least 95% of them within two leaves
/// of it, as degenerate_shape() judges), in their frame; nothing for a shape with relief. A flat
/// landmark (CaptureSettings::allow_flat) is the same wherever it lies on its plane.
std::optional<Eigen::Vector3d> flat_normal(const PointCloud& points, double leaf_size);

/// Throws lmk::Error, starting with `what`, naming the first capture setting out of its range.
void check_capture_settings(const CaptureSettings& settings, const std::string& what);

/// Sets the capture to prepare its frame as searches with `scene` prepare theirs: the up axis, the
/// base frame, the veil angle and the depth smoothing. A landmark and the scenes it is searched in
/// are then alike (lmk serve and lmk_node capture so).
void prepare_capture_as_search(const SceneSettings& scene, CaptureSettings& capture);

/// Throws lmk::Error, starting with `what`, for a box capture() refuses whatever the scene: a
/// non-positive or non-finite side, a pose that is not a finite rotation and translation, or a side
/// over settings.max_box_side. A service checks a request with it before it waits for a frame.
void check_capture_box(const Box& box, const CaptureSettings& settings, const std::string& what);

/// Cuts a landmark out of `scene`: the finite scene points inside the oriented `box` (given in the
/// scene frame), voxel-downsampled to settings.leaf_size. Throws lmk::Error for an empty name, a
/// box with a non-positive, non-finite or oversized side, a box with no scene point inside, too
/// few points, or a degenerate (flat or straight) shape.
Landmark capture(const PointCloud& scene, const Box& box, const std::string& name,
                 const CaptureSettings& settings = {});

}  // namespace lmk
