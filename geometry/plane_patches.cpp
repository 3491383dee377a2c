// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/plane_patches.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/statistics.h"

namespace lmk {

namespace {

// The fraction of the residuals' variance that a quadratic in the pixel coordinates explains,
// fitted by its normal equations (the coordinates centred on the patch, a few pixels across, keep
// them well conditioned).
double curvature_r2(const std::vector<double>& residuals, const std::vector<std::size_t>& pixels,
                    int width) {
  const auto w = static_cast<std::size_t>(width);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t i : pixels) mean += Eigen::Vector2d(double(i % w), double(i / w));
  mean /= static_cast<double>(pixels.size());
  Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> Atb = Eigen::Matrix<double, 6, 1>::Zero();
  double b_sum = 0.0, b_squares = 0.0;
  std::vector<Eigen::Matrix<double, 6, 1>> rows(pixels.size());
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    const Eigen::Vector2d x = Eigen::Vector2d(double(pixels[k] % w), double(pixels[k] / w)) - mean;
    rows[k] << 1.0, x.x(), x.y(), x.x() * x.x(), x.x() * x.y(), x.y() * x.y();
    AtA.selfadjointView<Eigen::Lower>().rankUpdate(rows[k]);
    Atb += rows[k] * residuals[k];
    b_sum += residuals[k];
    b_squares += residuals[k] * residuals[k];
  }
  const Eigen::Matrix<double, 6, 1> c = AtA.selfadjointView<Eigen::Lower>().ldlt().solve(Atb);
  double unexplained = 0.0;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    const double e = residuals[k] - rows[k].dot(c);
    unexplained += e * e;
  }
  const double total = b_squares - b_sum * b_sum / static_cast<double>(pixels.size());
  return total > 0.0 ? 1.0 - unexplained / total : 0.0;
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
  return median(gaps).value_or(std::nan(""));
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

}  // namespace

Eigen::Vector4d fit_ray_plane(const std::vector<Eigen::Vector3d>& points) {
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

PlanePatch measure_patch(const PatchPoints& pts, const Eigen::Vector4d& plane) {
  PlanePatch patch;
  patch.plane = plane;
  patch.points = pts.p.size();
  patch.pixels = pts.pixels;
  std::vector<double> residuals, depths;
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

std::optional<PlanePatch> plane_patch_at(const SensorPointAt& at, int width, int u0, int v0,
                                         const PlanePatchSettings& s) {
  const int tile = s.tile;
  const auto min_points = static_cast<std::size_t>(std::ceil(s.min_fill * tile * tile));
  PatchPoints pts;
  Eigen::Vector3d p;
  for (int v = v0; v < v0 + tile; ++v) {
    for (int u = u0; u < u0 + tile; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(u);
      if (!at(i, p) || !(p.z() > 0.0)) continue;
      pts.p.push_back(p);
      pts.pixels.push_back(i);
    }
  }
  if (pts.p.size() < min_points) return std::nullopt;
  const Eigen::Vector4d plane = fit_ray_plane(pts.p);
  std::vector<double> residuals;
  residuals.reserve(pts.p.size());
  for (const auto& q : pts.p) residuals.push_back(plane.head<3>().dot(q) + plane[3]);
  if (curvature_r2(residuals, pts.pixels, width) > s.max_curvature_r2) return std::nullopt;
  return measure_patch(pts, plane);
}

}  // namespace lmk
