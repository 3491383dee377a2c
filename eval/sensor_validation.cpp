// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/sensor_validation.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "lmk/eval/scene_types.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/statistics.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

double median_value(const std::vector<double>& values) { return median(values).value_or(NAN); }

// Points of one patch in the sensor frame, with their pixel coordinates.
struct PatchPoints {
  std::vector<Eigen::Vector3d> p;
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::size_t> pixels;
};

// The plane through the points, fitted where a depth camera's error lies: along the rays. A plane
// n.p + d = 0 seen through the ray (x', y', 1) = p / z is linear in inverse depth,
// 1/z = -(n.(x', y', 1)) / d, so a least-squares fit of 1/z to (x', y', 1) gives it without the
// degeneracy of a principal-axes fit on a patch hardly wider than its noise.
Eigen::Vector4d fit_plane(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d ray = p / p.z();
    AtA += ray * ray.transpose();
    Atb += ray / p.z();
  }
  const Eigen::Vector3d coefficients = AtA.ldlt().solve(Atb);  // 1/z = coefficients . ray
  const double norm = coefficients.norm();
  // n = -d coefficients with |n| = 1 and the normal facing the sensor (d > 0).
  const Eigen::Vector3d n = -coefficients / norm;
  return Eigen::Vector4d(n.x(), n.y(), n.z(), 1.0 / norm);
}

// The fraction of the residuals' variance that a quadratic in the pixel coordinates explains.
double curvature_r2(const std::vector<double>& residuals, const std::vector<Eigen::Vector2d>& uv) {
  const Eigen::Index n = static_cast<Eigen::Index>(residuals.size());
  Eigen::MatrixXd A(n, 6);
  Eigen::VectorXd b(n);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& x : uv) mean += x;
  mean /= static_cast<double>(uv.size());
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d x = uv[static_cast<std::size_t>(i)] - mean;
    A.row(i) << 1.0, x.x(), x.y(), x.x() * x.x(), x.x() * x.y(), x.y() * x.y();
    b[i] = residuals[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd fit = A * A.colPivHouseholderQr().solve(b);
  const double total = (b.array() - b.mean()).square().sum();
  return total > 0.0 ? 1.0 - (b - fit).squaredNorm() / total : 0.0;
}

// The median gap between consecutive distinct depths (levels closer than 0.05 mm are one level,
// float rounding); NaN with fewer than three levels.
double median_level_gap(std::vector<double> depths) {
  std::sort(depths.begin(), depths.end());
  std::vector<double> levels;
  for (double z : depths) {
    if (levels.empty() || z - levels.back() > 5e-5) levels.push_back(z);
  }
  if (levels.size() < 3) return std::nan("");
  std::vector<double> gaps;
  for (std::size_t i = 1; i < levels.size(); ++i) gaps.push_back(levels[i] - levels[i - 1]);
  return median_value(gaps);
}

// The standard deviation after dropping, twice, what lies beyond 3 of them from the mean: robust
// to the odd flying pixel, and unlike the median absolute deviation still meaningful when most of
// a patch lies on one or two depth levels.
double clipped_sd(const std::vector<double>& values) {
  double mean = 0.0, sd = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 3; ++pass) {
    double sum = 0.0, sum2 = 0.0;
    std::size_t n = 0;
    for (double v : values) {
      if (std::abs(v - mean) > 3.0 * sd) continue;
      sum += v;
      sum2 += v * v;
      ++n;
    }
    if (n < 2) break;
    mean = sum / static_cast<double>(n);
    sd = std::sqrt(std::max(0.0, sum2 / static_cast<double>(n) - mean * mean));
  }
  return sd;
}

// The statistics of a patch's points about `plane` (fitted to them, or to their real twins).
PlanePatch measure(const PatchPoints& pts, const Eigen::Vector4d& plane) {
  PlanePatch patch;
  patch.plane = plane;
  patch.points = pts.p.size();
  patch.pixels = pts.pixels;
  std::vector<double> residuals, depths, abs_dev;
  double depth = 0.0;
  for (const auto& p : pts.p) {
    residuals.push_back(plane.head<3>().dot(p) + plane[3]);
    depths.push_back(p.z());
    depth += p.z();
  }
  patch.depth = depth / static_cast<double>(pts.p.size());
  patch.residual_sd = clipped_sd(residuals);
  patch.level_spacing = median_level_gap(depths);
  return patch;
}

}  // namespace

std::vector<PlanePatch> plane_patches(const PointCloud& frame, const std::vector<bool>& keep,
                                      const PlanePatchSettings& s) {
  if (frame.height <= 1 || frame.points.size() != std::size_t{frame.width} * frame.height)
    throw Error("sensor validation: the frame must be an organised depth image");
  if (!keep.empty() && keep.size() != frame.size())
    throw Error("sensor validation: the point filter must have one entry per point");
  const Eigen::Isometry3d T_sensor_cloud = frame.T_cloud_sensor.inverse();
  const int tile = s.tile;
  const auto min_points = static_cast<std::size_t>(std::ceil(s.min_fill * tile * tile));
  std::vector<PlanePatch> out;
  for (int v0 = 0; v0 + tile <= static_cast<int>(frame.height); v0 += tile) {
    for (int u0 = 0; u0 + tile <= static_cast<int>(frame.width); u0 += tile) {
      PatchPoints pts;
      for (int v = v0; v < v0 + tile; ++v) {
        for (int u = u0; u < u0 + tile; ++u) {
          const std::size_t i = static_cast<std::size_t>(v) * frame.width + u;
          if (!is_finite(frame.points[i]) || (!keep.empty() && !keep[i])) continue;
          pts.p.push_back(T_sensor_cloud * frame.points[i].cast<double>());
          pts.uv.emplace_back(u, v);
          pts.pixels.push_back(i);
        }
      }
      if (pts.p.size() < min_points) continue;
      const Eigen::Vector4d plane = fit_plane(pts.p);
      std::vector<double> residuals;
      for (const auto& p : pts.p) residuals.push_back(plane.head<3>().dot(p) + plane[3]);
      if (curvature_r2(residuals, pts.uv) > s.max_curvature_r2) continue;
      out.push_back(measure(pts, plane));
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
  return measure(pts, fit_plane(pts.p));
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
