// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/frame_noise.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "lmk/geometry/statistics.h"

namespace lmk {

namespace {

// The image's tiles, each fitted at most once however often the window around a pixel grows.
class TileCache {
 public:
  TileCache(const RangeImage& image, const PlanePatchSettings& settings)
      : image_(image),
        settings_(settings),
        columns_(image.intrinsics().width / settings.tile),
        rows_(image.intrinsics().height / settings.tile),
        state_(static_cast<std::size_t>(std::max(0, columns_ * rows_)), kUnfitted),
        patch_(state_.size()) {}

  int columns() const { return columns_; }
  int rows() const { return rows_; }

  // The planar patch of tile (column, row), or nothing when the tile is no plane.
  const std::optional<PlanePatch>& patch(int column, int row) {
    fit(column, row);
    return patch_[static_cast<std::size_t>(row * columns_ + column)];
  }

  // Fits every tile of [c0, c1) x [r0, r1) (clamped to the image) not fitted yet, in parallel:
  // a window grown to find its patches holds hundreds of tiles, each fitted on its own.
  void fit_all(int c0, int c1, int r0, int r1) {
    c0 = std::max(c0, 0), r0 = std::max(r0, 0);
    c1 = std::min(c1, columns_), r1 = std::min(r1, rows_);
    if (c0 >= c1 || r0 >= r1) return;
    const int width = c1 - c0;
    tbb::parallel_for(0, width * (r1 - r0), [&](int k) { fit(c0 + k % width, r0 + k / width); });
  }

 private:
  void fit(int column, int row) {
    const auto t = static_cast<std::size_t>(row * columns_ + column);
    if (state_[t] == kFitted) return;
    patch_[t] = plane_patch_at(point_at(), image_.intrinsics().width, column * settings_.tile,
                               row * settings_.tile, settings_);
    state_[t] = kFitted;
  }

  static constexpr char kUnfitted = 0, kFitted = 1;

  // A pixel's point in the sensor frame, back-projected through the image's intrinsics.
  SensorPointAt point_at() const {
    const PinholeIntrinsics& k = image_.intrinsics();
    const std::vector<float>& depths = image_.depths();
    return [&k, &depths](std::size_t i, Eigen::Vector3d& p) {
      const double z = depths[i];
      if (!(z > 0.0)) return false;  // NaN: nothing measured
      const double u = static_cast<double>(i % static_cast<std::size_t>(k.width));
      const double v = static_cast<double>(i / static_cast<std::size_t>(k.width));
      p = Eigen::Vector3d((u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z);
      return true;
    };
  }

  const RangeImage& image_;
  PlanePatchSettings settings_;
  int columns_, rows_;
  std::vector<char> state_;
  std::vector<std::optional<PlanePatch>> patch_;
};

// The axial spreads, scaled to `depth`, of the planar patches at that depth among tiles [c0, c1) x
// [r0, r1). A patch's spread about its plane is the axial noise foreshortened by the cosine between
// its normal and its ray; patches seen more obliquely than kMaxNoiseIncidence are left out, where
// undoing that would magnify every error of the fit.
void collect(TileCache& tiles, const PinholeIntrinsics& k, double tile, int c0, int c1, int r0,
             int r1, double depth, std::vector<double>& out) {
  const double min_cosine = std::cos(kMaxNoiseIncidence);
  for (int r = std::max(r0, 0); r < std::min(r1, tiles.rows()); ++r) {
    for (int c = std::max(c0, 0); c < std::min(c1, tiles.columns()); ++c) {
      const std::optional<PlanePatch>& patch = tiles.patch(c, r);
      if (!patch || std::abs(patch->depth - depth) > kNoiseDepthBand * depth) continue;
      const Eigen::Vector3d ray = Eigen::Vector3d(((c + 0.5) * tile - 0.5 - k.cx) / k.fx,
                                                  ((r + 0.5) * tile - 0.5 - k.cy) / k.fy, 1.0)
                                      .normalized();
      const double cosine = std::abs(ray.dot(patch->plane.head<3>()));
      if (cosine < min_cosine) continue;
      const double scale = depth / patch->depth;
      out.push_back(patch->residual_sd / cosine * scale * scale);
    }
  }
}

}  // namespace

MeasuredNoise measure_noise_near(const RangeImage& image, const Eigen::Vector2d& pixel,
                                 double depth, double min_window,
                                 const PlanePatchSettings& settings) {
  MeasuredNoise out;
  if (!image.organised() || !(depth > 0.0) || !pixel.allFinite() || settings.tile < 2) return out;
  TileCache tiles(image, settings);
  const double tile = settings.tile;
  const double largest = std::max(image.intrinsics().width, image.intrinsics().height);
  std::vector<double> spreads;
  for (double window = std::max(min_window, tile);; window *= 2.0) {
    // The tiles whose pixels the window touches; those of a smaller window are fitted once.
    const int c0 = static_cast<int>(std::floor((pixel.x() - window) / tile));
    const int c1 = static_cast<int>(std::floor((pixel.x() + window) / tile)) + 1;
    const int r0 = static_cast<int>(std::floor((pixel.y() - window) / tile));
    const int r1 = static_cast<int>(std::floor((pixel.y() + window) / tile)) + 1;
    tiles.fit_all(c0, c1, r0, r1);
    spreads.clear();
    collect(tiles, image.intrinsics(), tile, c0, c1, r0, r1, depth, spreads);
    out.window = window;
    if (spreads.size() >= kMinNoisePatches || window >= largest) break;
  }
  out.patches = spreads.size();
  if (out.measured()) out.sigma = median(spreads).value_or(out.sigma);
  return out;
}

MeasuredNoise measure_noise_at(const RangeImage& image, const Eigen::Vector3f& point,
                               double min_window) {
  const std::optional<Eigen::Vector2d> pixel = image.project(point);
  if (!pixel) return {};
  return measure_noise_near(image, *pixel, image.depth_of(point), min_window);
}

}  // namespace lmk
