// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/sensor_validation.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/statistics.h"
#include "lmk/sim/scene_types.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

double median_value(const std::vector<double>& values) { return median(values).value_or(NAN); }

}  // namespace

std::vector<PlanePatch> plane_patches(const PointCloud& frame, const std::vector<bool>& keep,
                                      const PlanePatchSettings& s) {
  if (frame.height <= 1 || frame.points.size() != std::size_t{frame.width} * frame.height)
    throw Error("sensor validation: the frame must be an organised depth image");
  if (!keep.empty() && keep.size() != frame.size())
    throw Error("sensor validation: the point filter must have one entry per point");
  const Eigen::Isometry3d T_sensor_cloud = frame.T_cloud_sensor.inverse();
  const SensorPointAt at = [&](std::size_t i, Eigen::Vector3d& p) {
    if (!is_finite(frame.points[i]) || (!keep.empty() && !keep[i])) return false;
    p = T_sensor_cloud * frame.points[i].cast<double>();
    return true;
  };
  const int width = static_cast<int>(frame.width), height = static_cast<int>(frame.height);
  std::vector<PlanePatch> out;
  for (int v0 = 0; v0 + s.tile <= height; v0 += s.tile) {
    for (int u0 = 0; u0 + s.tile <= width; u0 += s.tile) {
      if (auto patch = plane_patch_at(at, width, u0, v0, s)) out.push_back(std::move(*patch));
    }
  }
  return out;
}

PlanePatch simulate_patch(const PointCloud& frame, const PlanePatch& patch,
                          const DepthSensorSettings& sensor, const std::vector<double>& noise) {
  const Eigen::Isometry3d T_sensor_cloud = frame.T_cloud_sensor.inverse();
  const Eigen::Vector3d n = patch.plane.head<3>();
  PatchPoints pts;
  for (std::size_t i : patch.pixels) {
    // The real point lies on its pixel's ray, so its direction is the ray: no intrinsics needed.
    const Eigen::Vector3d seen = T_sensor_cloud * frame.points[i].cast<double>();
    const Eigen::Vector3d ray = seen / seen.z();
    const double z = -patch.plane[3] / n.dot(ray);  // where the ray meets the fitted plane
    if (!(z > 0.0)) continue;
    pts.p.push_back(ray * sensor_depth(z, noise[i], sensor));
    pts.pixels.push_back(i);
  }
  if (pts.p.empty()) return PlanePatch();
  return measure_patch(pts, fit_ray_plane(pts.p));
}

SensorValidation::SensorValidation(DepthSensorSettings sensor, double bin_width,
                                   PlanePatchSettings patches)
    : sensor_(sensor), bin_width_(bin_width), patch_settings_(patches) {
  if (!(bin_width > 0.0)) throw Error("sensor validation: the bin width must be positive");
}

std::size_t SensorValidation::add_frame(const PointCloud& frame, const std::vector<bool>& keep) {
  DepthSensorSettings sensor = sensor_;
  sensor.seed = sensor_.seed + frames_++;  // independent noise per frame
  sensor.width = static_cast<int>(frame.width);
  sensor.height = static_cast<int>(frame.height);
  const std::vector<double> noise = sensor_noise_field(sensor);
  std::size_t added = 0;
  for (PlanePatch& patch : plane_patches(frame, keep, patch_settings_)) {
    // Only depths the simulated sensor returns; the real one reaches farther.
    if (patch.depth < sensor.min_range || patch.depth > sensor.max_range) continue;
    PlanePatch twin = simulate_patch(frame, patch, sensor, noise);
    if (twin.points == 0) continue;
    patch.pixels.clear();
    twin.pixels.clear();
    real_.push_back(std::move(patch));
    simulated_.push_back(std::move(twin));
    ++added;
  }
  return added;
}

std::vector<SensorRangeComparison> SensorValidation::compare(std::size_t min_patches) const {
  std::vector<SensorRangeComparison> out;
  if (real_.empty()) return out;
  const auto bin_of = [this](double depth) {
    return static_cast<long>(std::floor(depth / bin_width_));
  };
  long first = bin_of(real_.front().depth), last = first;
  for (const PlanePatch& p : real_) {
    first = std::min(first, bin_of(p.depth));
    last = std::max(last, bin_of(p.depth));
  }
  for (long bin = first; bin <= last; ++bin) {
    std::vector<double> real_sd, sim_sd, real_gap, sim_gap, depth;
    for (std::size_t i = 0; i < real_.size(); ++i) {
      if (bin_of(real_[i].depth) != bin) continue;
      real_sd.push_back(real_[i].residual_sd);
      sim_sd.push_back(simulated_[i].residual_sd);
      depth.push_back(real_[i].depth);
      // Spacing only where both show at least three levels.
      if (!std::isnan(real_[i].level_spacing) && !std::isnan(simulated_[i].level_spacing)) {
        real_gap.push_back(real_[i].level_spacing);
        sim_gap.push_back(simulated_[i].level_spacing);
      }
    }
    if (real_sd.size() < min_patches || real_gap.empty()) continue;
    SensorRangeComparison c;
    c.min_depth = static_cast<double>(bin) * bin_width_;
    c.max_depth = c.min_depth + bin_width_;
    c.patches = real_sd.size();
    c.real_residual_sd = median_value(real_sd);
    c.simulated_residual_sd = median_value(sim_sd);
    c.real_level_spacing = median_value(real_gap);
    c.simulated_level_spacing = median_value(sim_gap);
    c.model_level_spacing = depth_level_spacing(median_value(depth), sensor_);
    out.push_back(c);
  }
  return out;
}

DepthEdgeCount count_depth_edges(const PointCloud& cloud) {
  DepthEdgeCount count;
  if (cloud.height <= 1 || cloud.points.size() != std::size_t{cloud.width} * cloud.height)
    return count;
  const Eigen::Isometry3d T_sensor_cloud = cloud.T_cloud_sensor.inverse();
  const auto depth = [&](std::size_t i) {
    return (T_sensor_cloud * cloud.points[i].cast<double>()).z();
  };
  for (std::uint32_t v = 0; v < cloud.height; ++v) {
    for (std::uint32_t u = 1; u + 1 < cloud.width; ++u) {
      const std::size_t i = std::size_t{v} * cloud.width + u;
      if (!is_finite(cloud.points[i - 1]) || !is_finite(cloud.points[i]) ||
          !is_finite(cloud.points[i + 1]))
        continue;
      const double a = depth(i - 1), b = depth(i + 1), z = depth(i);
      const double near = std::min(a, b), far = std::max(a, b);
      if (far - near < 0.05 * near) continue;
      ++count.edges;
      if (z > 1.015 * near && z < far / 1.015) ++count.mixed;
    }
  }
  return count;
}

DepthEdgeCount simulated_depth_edges(
    const DepthSensorSettings& sensor,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  // Flying pixels need whole scenes with depth edges: the benchmark's, seen by the model.
  const std::vector<std::string>& types = scene_types();
  DepthEdgeCount count;
  for (std::size_t i = 0; i < types.size(); ++i) {
    const GeneratedScene scene = make_scene(types[i], 1, false);
    DepthSensorSettings s = sensor;
    s.seed = i;
    count.add(count_depth_edges(render_depth(scene.mesh, scene.T_world_sensor, s)));
    if (progress) progress(i + 1, types.size());
  }
  return count;
}

std::vector<std::string> sensor_validation_files(const std::string& data_dir) {
  std::vector<std::string> files;
  const fs::path mosd = fs::path(data_dir) / "mosd" / "learn";
  for (int i = 0; fs::exists(mosd / ("learn" + std::to_string(i) + ".pcd")); ++i)
    files.push_back((mosd / ("learn" + std::to_string(i) + ".pcd")).string());
  // table_scene_mug_stereo_textured.pcd comes from a stereo camera, not a Kinect.
  for (const char* name :
       {"milk_cartoon_all_small_clorox.pcd", "office1.pcd", "five_people.pcd",
        "grabber_frame_20121214T142255.814212.pcd", "grabber_frame_20121214T142256.068683.pcd",
        "grabber_frame_20121214T142256.332395.pcd"}) {
    const fs::path path = fs::path(data_dir) / "pcl" / name;
    if (fs::exists(path)) files.push_back(path.string());
  }
  return files;
}

RealFrame load_sensor_validation_frame(const std::string& path) {
  RealFrame frame;
  frame.cloud = read_cloud(path);
  // These frames are all in the depth camera's optical frame, but office1.pcd declares a
  // VIEWPOINT turned 180 degrees about x, under which every point would lie behind the sensor. A
  // viewpoint that puts most points behind the sensor is taken as wrong and replaced by the
  // camera's own frame.
  const Eigen::Isometry3d T_sensor_cloud = frame.cloud.T_cloud_sensor.inverse();
  std::size_t behind = 0, finite = 0;
  for (const Eigen::Vector3f& p : frame.cloud.points) {
    if (!is_finite(p)) continue;
    ++finite;
    if ((T_sensor_cloud * p.cast<double>()).z() < 0.0) ++behind;
  }
  if (2 * behind > finite) frame.cloud.T_cloud_sensor = Eigen::Isometry3d::Identity();
  if (frame.cloud.has_labels()) {
    frame.keep.resize(frame.cloud.size());
    for (std::size_t i = 0; i < frame.cloud.size(); ++i) {
      const std::int32_t label = frame.cloud.labels[i];
      frame.keep[i] = label >= 1 && label < 20;  // 1-9: table and background; 20 on: objects
    }
  }
  return frame;
}

}  // namespace lmk
