// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// SceneSettings: steps 1-2 of the search, the scene's crop, leaves and grids, and which way is up
// (geometry/settings_schema.h describes each field once for validation, JSON and the CLI).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/depth_smoothing.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/geometry/voxel_grid.h"

namespace lmk {

/// The largest scene leaves (leaf_size, coarse_leaf), m.
constexpr double kMaxSceneLeaf = 0.1;
/// The distance-field band holds at most this many coarse leaves.
constexpr double kMaxFieldBandLeaves = 10.0;
/// Farther than any depth camera sees, m: the bound of lengths measured from the sensor.
constexpr double kMaxSensorRange = 20.0;

/// Which of a landmark's points the visibility and projective metrics leave uncounted when the
/// scene's sensor could not have seen them (SceneSettings::unseen_points): none (`counted`, the
/// default), those that fall outside the scene's image (`outside-image`), and also those that fall
/// on a pixel where the sensor measured nothing (`no-return`). Either way a pose must still show
/// half the landmark (kMinShownShare, search/metrics/grid_metrics.h).
enum class UnseenPoints { counted, outside_image, no_return };
const std::vector<std::string>& setting_names(UnseenPoints);

struct SceneSettings {
  /// Step 1: crop the scene to this box (scene frame) first; nothing means the whole scene.
  std::optional<Box> work_volume;
  double leaf_size = 0.005;   ///< step 2, the paper's leaf: fine points and occupancy voxels, m
  double coarse_leaf = 0.01;  ///< seeds, voting and coarse alignment, m; at least leaf_size
  /// Band of the scene distance field, m; at least coarse_leaf. Unset: twice the coarse leaf, so
  /// that a candidate a voxel off still finds its surface.
  std::optional<double> field_band;
  std::optional<Eigen::Vector3d> up;  ///< up axis in the scene frame; unset: default_up()
  bool base_frame = false;            ///< the scene is in a robot base frame (+z up)
  /// The depth sensor's axial noise coefficient, m^-1 (sigma = noise_axial z^2; Kinect v1's by
  /// default) and the residual that remains at any depth, m: the unit of the sensor metric.
  double noise_axial = DepthNoise().axial;
  double noise_floor = DepthNoise().floor;
  /// An organised frame's veil points (geometry/veil_points.h: steps within this angle of the
  /// sensor's rays) are dropped before anything is built, rad; 0 (the default) keeps them. Off by
  /// default: at 10 degrees it raised recall on the real desk sequence (0.265 -> 0.296) but cost
  /// the synthetic frames, which have no veil, real points (docs/evaluation.md).
  double veil_angle = 0.0;
  /// An organised frame's depth is smoothed over a window of this many pixels around each point
  /// (geometry/depth_smoothing.h) before anything is built, as a capture smooths its frame
  /// (CaptureSettings::depth_smoothing); 0: the raw depth.
  int depth_smoothing = kDefaultDepthSmoothing;
  /// Visibility and projective metrics: the threshold holds as given up to this distance from the
  /// scene's sensor, m. Beyond it, a candidate's error is scaled down by how much the depth noise
  /// there raises the error a true match shows (match_error_scale(), grid_metrics.h). Unset (the
  /// default): one threshold in metres at every range. On the real kitchen sequence 1.5 m raised
  /// recall in context from 0.385 to 0.600, but on the synthetic `viewpoints` preset, whose true
  /// matches stay under the threshold at range, it let look-alikes in at 2-3 m (precision 0.947 ->
  /// 0.669): an option for real far frames, not a default (docs/evaluation.md).
  std::optional<double> threshold_range;
  /// Visibility and projective metrics: the landmark points an organised scene's sensor could not
  /// have seen, which count neither way. Counted by default: on real frames a landmark at the
  /// image's edge lost the points beyond it to the band (the kitchen's instances within 2 m were
  /// found 0.625 -> 0.775 with `outside-image`), but on the synthetic `viewpoints` preset it let a
  /// look-alike in (precision 0.947 -> 0.940; docs/evaluation.md).
  UnseenPoints unseen_points = UnseenPoints::counted;

  /// These settings with field_band spelt out: what a SceneIndex applies.
  SceneSettings resolved() const {
    SceneSettings r = *this;
    if (!r.field_band) r.field_band = 2.0 * coarse_leaf;
    return r;
  }
  DepthNoise depth_noise() const {
    DepthNoise noise;
    noise.axial = noise_axial;
    noise.floor = noise_floor;
    return noise;
  }

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("work_volume",
                      "Crop the scene to this box first: CX CY CZ SX SY SZ [ROLL PITCH YAW], m and "
                      "degrees (default: the whole scene)"),
          s.work_volume);
    // Leaves up to 10 cm: a landmark of a few tens of cm is then a few voxels across, and a
    // coarser grid describes no shape at all.
    visit(SettingInfo("leaf_size", "Scene voxel leaf (the paper's 5 mm), m; at least 1 mm")
              .within(kMinLeafSize, kMaxSceneLeaf)
              .also("leaf"),
          s.leaf_size);
    visit(SettingInfo("coarse_leaf",
                      "Fast: leaf of the seeds, voting and coarse alignment, m; at least 1 mm")
              .within(kMinLeafSize, kMaxSceneLeaf),
          s.coarse_leaf);
    // Up to 20 cm, twice the largest leaf; validate() also holds it within kMaxFieldBandLeaves
    // coarse leaves. The field's voxels grow with the band times the scene's surface: 1e308 held
    // the server at 4.8 GB, 5 m ran for minutes (issue #34), and a candidate further than a few
    // leaves from the surface is hopeless anyway.
    visit(
        SettingInfo("field_band", "Band of the scene distance field, m (default: 2 coarse leaves)")
            .within(kMinLeafSize, 2.0 * kMaxSceneLeaf),
        s.field_band);
    visit(SettingInfo("up",
                      "Up axis X Y Z in the scene frame (default: the sensor's -y, or +z "
                      "with --base-frame)"),
          s.up);
    visit(SettingInfo("base_frame", "The scene is expressed in a robot base frame, whose +z is up"),
          s.base_frame);
    visit(SettingInfo("noise_axial",
                      "Sensor metric: depth noise coefficient, sigma = this x depth^2, 1/m "
                      "(Kinect v1's)")
              .within(0.0, 0.1),
          s.noise_axial);
    // A residual of 10 cm at every depth would make any surface match any other.
    visit(SettingInfo("noise_floor", "Sensor metric: residual at any depth, m")
              .positive()
              .at_most(0.1),
          s.noise_floor);
    visit(SettingInfo("veil_angle",
                      "Drop an organised frame's veil points: steps within this angle of the "
                      "sensor's rays (default 0: keep them; 10 helped near RealSense frames, not a "
                      "Kinect's at 2 m)")
              .within(0.0, 0.5236)
              .in_degrees(),
          s.veil_angle);
    visit(SettingInfo("depth_smoothing",
                      "Smooth an organised frame's depth over this many pixels around each point, "
                      "within 3 of the sensor's depth levels (0: the raw depth)")
              .within(0, kMaxDepthSmoothingRadius),
          s.depth_smoothing);
    visit(SettingInfo("threshold_range",
                      "Visibility metrics: the threshold holds up to this range, m; beyond, errors "
                      "are scaled down as the depth noise raises a true match's (default: never)")
              .positive()
              .at_most(kMaxSensorRange),  // beyond any depth camera's range
          s.threshold_range);
    visit(SettingInfo(
              "unseen_points",
              "Visibility metrics: leave uncounted the landmark points an organised scene's "
              "sensor could not see: counted (every point counts), outside-image, no-return (also "
              "those on pixels without a return)")
              .names_of<UnseenPoints>(),
          s.unseen_points);
  }
};

/// Throws lmk::Error for settings out of their limits, and for leaves out of order (the coarse
/// leaf below the leaf, the field band below the coarse leaf).
void validate(const SceneSettings& settings);

}  // namespace lmk
