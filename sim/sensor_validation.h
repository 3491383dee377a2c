// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulated Kinect checked against real frames: planar patches of real Kinect clouds (tables,
// walls, floors) are fitted, then the very same pixels are re-measured by the sensor model
// (sensor_depth) from the fitted plane, so that geometry, incidence and pixel set are identical
// and only the sensor differs. Per range, the two are compared on
// - the residual spread about the plane (a robust standard deviation), and
// - the spacing of the depth levels (the disparity's quantisation, then the driver's millimetres).

#include <functional>
#include <string>
#include <vector>

#include "lmk/geometry/plane_patches.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk {

/// The planar patches of an organised frame, among the points `keep` accepts (empty: all).
/// Throws lmk::Error for an unorganised frame.
std::vector<PlanePatch> plane_patches(const PointCloud& frame, const std::vector<bool>& keep = {},
                                      const PlanePatchSettings& settings = {});

/// The same pixels as `patch`, measured by the sensor model from the patch's fitted plane, with
/// the frame's noise `noise` (sensor_noise_field of the frame's size).
PlanePatch simulate_patch(const PointCloud& frame, const PlanePatch& patch,
                          const DepthSensorSettings& sensor, const std::vector<double>& noise);

/// Real against simulated, over the patches whose depth lies in [min_depth, max_depth).
struct SensorRangeComparison {
  double min_depth = 0.0, max_depth = 0.0;
  std::size_t patches = 0;
  double real_residual_sd = 0.0, simulated_residual_sd = 0.0;      ///< medians over patches, m
  double real_level_spacing = 0.0, simulated_level_spacing = 0.0;  ///< medians over patches, m
  double model_level_spacing = 0.0;  ///< depth_level_spacing at the bin's median depth, m
};

/// Accumulates patches of many frames and compares them per depth bin.
class SensorValidation {
 public:
  explicit SensorValidation(DepthSensorSettings sensor = {}, double bin_width = 0.25,
                            PlanePatchSettings patches = {});

  /// Adds the planar patches of one real frame (and their simulated twins). Returns how many.
  std::size_t add_frame(const PointCloud& frame, const std::vector<bool>& keep = {});

  /// One comparison per depth bin holding at least `min_patches` patches, nearest first.
  std::vector<SensorRangeComparison> compare(std::size_t min_patches = 20) const;

 private:
  DepthSensorSettings sensor_;
  double bin_width_;
  PlanePatchSettings patch_settings_;
  std::size_t frames_ = 0;
  std::vector<PlanePatch> real_, simulated_;
};

/// Flying pixels, counted along image rows: of the pixels whose two neighbours differ in depth by
/// more than 5% (a depth edge), those whose own depth lies between the neighbours', at least 1.5%
/// from each: a mixed return.
struct DepthEdgeCount {
  std::size_t edges = 0, mixed = 0;
  void add(const DepthEdgeCount& other) {
    edges += other.edges;
    mixed += other.mixed;
  }
  double rate() const {
    return edges ? static_cast<double>(mixed) / static_cast<double>(edges) : 0.0;
  }
};
DepthEdgeCount count_depth_edges(const PointCloud& organised);

/// The simulated side of that count: the benchmark's scene types (seed 1), rendered by `sensor`,
/// each with its own noise seed. `progress` is called after each scene with (done, in all).
DepthEdgeCount simulated_depth_edges(
    const DepthSensorSettings& sensor,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The real Kinect frames of the shared data (../shared/data layout) that the validation uses:
/// mOSD's learn frames and the PCL frames from a Kinect (not the stereo one). Missing files are
/// left out.
std::vector<std::string> sensor_validation_files(const std::string& data_dir);

/// One of them, with the points the validation keeps: in mOSD frames the table and background
/// (label 1), not the objects; in the others every point (the patch test keeps the planes).
struct RealFrame {
  PointCloud cloud;
  std::vector<bool> keep;
};
RealFrame load_sensor_validation_frame(const std::string& path);

}  // namespace lmk
