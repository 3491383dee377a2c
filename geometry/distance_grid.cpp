// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/distance_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"

namespace lmk {

namespace {

constexpr float kFar = 1e20f;  // "no occupied voxel yet", squared voxels

// One line of the squared distance transform (Felzenszwalb & Huttenlocher 2012, Algorithm 1):
// d[q] = min_p (q - p)^2 + f[p], the lower envelope of the parabolas rooted at each p.
void transform_line(const std::vector<float>& f, std::vector<float>& d, std::vector<int>& v,
                    std::vector<float>& z) {
  const int n = static_cast<int>(f.size());
  int k = -1;  // the envelope's last parabola; none yet
  float s = 0.0f;
  for (int q = 0; q < n; ++q) {
    if (f[q] >= kFar) continue;  // an empty voxel roots no parabola
    while (k >= 0) {
      s = ((f[q] + static_cast<float>(q) * q) - (f[v[k]] + static_cast<float>(v[k]) * v[k])) /
          (2.0f * (q - v[k]));
      if (s > z[k]) break;
      --k;  // parabola k is nowhere lowest any more
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kFar : s;
    z[k + 1] = kFar;
  }
  if (k < 0) {  // nothing occupied on this line
    std::fill(d.begin(), d.end(), kFar);
    return;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = static_cast<float>(q - v[k]) * (q - v[k]) + f[v[k]];
  }
}

}  // namespace

DistanceGrid::DistanceGrid(const Eigen::Vector3d& min, const Eigen::Vector3d& max, double voxel,
                           std::size_t max_voxels)
    : min_(min), voxel_(voxel) {
  if (!(voxel > 0.0)) throw Error("distance grid: the voxel must be positive");
  if (!((max - min).array() > 0.0).all()) throw Error("distance grid: the box is empty");
  const Eigen::Vector3d cells = ((max - min) / voxel).array().ceil();
  if (cells.prod() > static_cast<double>(max_voxels)) {
    throw Error("distance grid: " + std::to_string(static_cast<long long>(cells.prod())) +
                " voxels, more than " + std::to_string(max_voxels));
  }
  dims_ = cells.cast<int>();
  cells_.assign(static_cast<std::size_t>(dims_.prod()), kFar);
}

Eigen::Vector3d DistanceGrid::centre(std::size_t i) const {
  const std::size_t x = i % dims_.x(), y = (i / dims_.x()) % dims_.y(),
                    z = i / (static_cast<std::size_t>(dims_.x()) * dims_.y());
  return min_ + voxel_ * (Eigen::Vector3d(x, y, z).array() + 0.5).matrix();
}

void DistanceGrid::occupy(const Eigen::Vector3d& p) {
  const Eigen::Vector3d c = ((p - min_) / voxel_).array().floor();
  if ((c.array() < 0.0).any() || (c.array() >= dims_.cast<double>().array()).any()) return;
  cells_[index(c.cast<int>())] = 0.0f;
}

void DistanceGrid::compute() {
  // Squared distances axis by axis, in voxels; then metres.
  const int longest = dims_.maxCoeff();
  std::vector<float> f(longest), d(longest), z(longest + 1);
  std::vector<int> v(longest);
  for (int axis = 0; axis < 3; ++axis) {
    const int n = dims_[axis];
    f.resize(n);
    d.resize(n);
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int j = 0; j < dims_[b]; ++j) {
      for (int i = 0; i < dims_[a]; ++i) {
        Eigen::Vector3i c;
        c[a] = i;
        c[b] = j;
        for (int q = 0; q < n; ++q) {
          c[axis] = q;
          f[q] = cells_[index(c)];
        }
        transform_line(f, d, v, z);
        for (int q = 0; q < n; ++q) {
          c[axis] = q;
          cells_[index(c)] = d[q];
        }
      }
    }
  }
  for (float& c : cells_)
    c = c >= kFar ? std::numeric_limits<float>::infinity()
                  : static_cast<float>(std::sqrt(c) * voxel_);
  computed_ = true;
}

double DistanceGrid::distance(const Eigen::Vector3d& p) const {
  if (!computed_) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d c = ((p - min_) / voxel_).array().floor();
  const Eigen::Vector3d top = dims_.cast<double>();
  if ((c.array() < 0.0).any() || (c.array() >= top.array()).any()) {
    // Outside: no nearer than the grid's box, and nothing of the grid's is known to be nearer.
    const Eigen::Vector3d max = min_ + voxel_ * top;
    return (min_ - p).cwiseMax(p - max).cwiseMax(0.0).norm();
  }
  return cells_[index(c.cast<int>())];
}

double DistanceGrid::error_bound() const { return voxel_ * std::sqrt(3.0); }

}  // namespace lmk
