// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/range_image.h"

#include <cmath>
#include <limits>

namespace lmk {

namespace {

constexpr float kNothing = std::numeric_limits<float>::quiet_NaN();

// Least squares of y = a x + b; false when x does not vary.
bool fit_line(double n, double sx, double sy, double sxx, double sxy, double& a, double& b) {
  const double det = n * sxx - sx * sx;
  if (!(std::abs(det) > 1e-12 * n * n)) return false;
  a = (n * sxy - sx * sy) / det;
  b = (sy - a * sx) / n;
  return true;
}

// Least squares of u = fx x/z + cx and v = fy y/z + cy over every pixel of organised `cloud` with a
// point in front of its sensor (`T_sensor_cloud`); false when too few pixels fix them.
bool fit_intrinsics(const PointCloud& cloud, const Eigen::Isometry3f& T_sensor_cloud,
                    PinholeIntrinsics& k) {
  double n = 0, sa = 0, su = 0, saa = 0, sau = 0, sb = 0, sv = 0, sbb = 0, sbv = 0;
  const std::uint32_t w = cloud.width;
  // Rows and columns as loop counters: a division and a modulo per pixel, twice over 300 000
  // pixels, cost more than the rest of the fit.
  const std::size_t size = cloud.size();
  for (std::size_t row = 0, i = 0; i < size; ++row) {
    const auto v = static_cast<double>(row);
    for (std::uint32_t column = 0; column < w && i < size; ++column, ++i) {
      const Eigen::Vector3f p = T_sensor_cloud * cloud.points[i];
      if (!p.allFinite() || !(p.z() > 0.0f)) continue;
      const double a = p.x() / p.z(), b = p.y() / p.z();
      const auto u = static_cast<double>(column);
      n += 1, sa += a, su += u, saa += a * a, sau += a * u;
      sb += b, sv += v, sbb += b * b, sbv += b * v;
    }
  }
  return n >= 100 && fit_line(n, sa, su, saa, sau, k.fx, k.cx) &&
         fit_line(n, sb, sv, sbb, sbv, k.fy, k.cy);
}

// The depth of every pixel of organised `cloud` through intrinsics `k`, into `depth`; the RMS of
// the pixels' distance from where `k` projects their points (infinity for no pixel).
double fill_depth(const PointCloud& cloud, const Eigen::Isometry3f& T_sensor_cloud,
                  const PinholeIntrinsics& k, std::vector<float>& depth) {
  const std::uint32_t w = cloud.width;
  const std::size_t size = cloud.size();
  double squared = 0.0, n = 0.0;
  depth.assign(size, kNothing);
  for (std::size_t row = 0, i = 0; i < size; ++row) {
    for (std::uint32_t column = 0; column < w && i < size; ++column, ++i) {
      const Eigen::Vector3f p = T_sensor_cloud * cloud.points[i];
      if (!p.allFinite() || !(p.z() > 0.0f)) continue;
      const double du = k.fx * p.x() / p.z() + k.cx - static_cast<double>(column);
      const double dv = k.fy * p.y() / p.z() + k.cy - static_cast<double>(row);
      squared += du * du + dv * dv;
      n += 1;
      depth[i] = p.z();
    }
  }
  return n > 0 ? std::sqrt(squared / n) : std::numeric_limits<double>::infinity();
}

}  // namespace

std::optional<RangeImage> RangeImage::from_cloud(const PointCloud& cloud,
                                                 const PinholeIntrinsics& fallback,
                                                 double max_fit_rms,
                                                 const PinholeIntrinsics* known) {
  RangeImage image;
  image.T_sensor_cloud_ = cloud.T_cloud_sensor.inverse().cast<float>();
  if (cloud.is_organized()) {
    if (cloud.width == 0) return std::nullopt;  // a malformed layout: no rows to fit
    PinholeIntrinsics& k = image.k_;
    k.width = static_cast<int>(cloud.width);
    k.height = static_cast<int>(cloud.height);
    // Known intrinsics of the same image size are kept when they fit these pixels as well as a
    // fit of its own must.
    const bool reuse =
        known && known->width == k.width && known->height == k.height &&
        fill_depth(cloud, image.T_sensor_cloud_, *known, image.depth_) <= max_fit_rms;
    if (reuse) {
      k = *known;
    } else {
      if (!fit_intrinsics(cloud, image.T_sensor_cloud_, k)) return std::nullopt;
      if (!(fill_depth(cloud, image.T_sensor_cloud_, k, image.depth_) <= max_fit_rms))
        return std::nullopt;
    }
    image.colour_ = cloud.colors;
    image.organised_ = true;
    return image;
  }
  image.k_ = fallback;
  image.depth_.assign(static_cast<std::size_t>(fallback.width) * fallback.height, kNothing);
  if (cloud.has_colors()) image.colour_.assign(image.depth_.size(), Color{0, 0, 0});
  bool any = false;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f p = image.T_sensor_cloud_ * cloud.points[i];
    const std::optional<std::size_t> pixel = image.pixel_of(p);
    if (!pixel) continue;
    float& d = image.depth_[*pixel];
    if (std::isnan(d) || p.z() < d) {
      d = p.z();
      if (cloud.has_colors()) image.colour_[*pixel] = cloud.colors[i];  // the nearest point's
    }
    any = true;
  }
  if (!any) return std::nullopt;
  return image;
}

std::optional<Eigen::Vector2d> RangeImage::project(const Eigen::Vector3f& point) const {
  const Eigen::Vector3f p = T_sensor_cloud_ * point;
  if (!p.allFinite() || !(p.z() > 0.0f)) return std::nullopt;
  return Eigen::Vector2d(k_.fx * p.x() / p.z() + k_.cx, k_.fy * p.y() / p.z() + k_.cy);
}

double RangeImage::depth_of(const Eigen::Vector3f& point) const {
  return (T_sensor_cloud_ * point).z();
}

std::optional<std::size_t> RangeImage::pixel_of(const Eigen::Vector3f& p) const {
  return k_.pixel_of(p.cast<double>(), k_.width, k_.height);
}

RangeImage::Look RangeImage::look(const Eigen::Vector3f& point) const {
  Look look;
  const Eigen::Vector3f p = T_sensor_cloud_ * point;
  look.depth = p.z();
  const std::optional<std::size_t> pixel = pixel_of(p);
  if (!pixel) return look;
  look.in_view = true;
  look.pixel = *pixel;
  look.measured = depth_[*pixel];
  return look;
}

}  // namespace lmk
