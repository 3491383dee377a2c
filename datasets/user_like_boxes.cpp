// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/user_like_boxes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>

#include "lmk/geometry/error.h"
#include "lmk/geometry/voxel_normals.h"

namespace lmk {
namespace {

struct Cell {
  std::vector<Eigen::Vector3f> points, normals;
};

// Whether the box's eight corners project into the image, in front of the camera.
bool projects_inside(const Box& box, const PinholeIntrinsics& k, std::uint32_t width,
                     std::uint32_t height) {
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d local(((c & 1) ? 0.5 : -0.5) * box.size.x(),
                                ((c & 2) ? 0.5 : -0.5) * box.size.y(),
                                ((c & 4) ? 0.5 : -0.5) * box.size.z());
    const Eigen::Vector3d p = box.pose * local;
    if (!(p.z() > 0.0)) return false;
    const double u = k.fx * p.x() / p.z() + k.cx;
    const double v = k.fy * p.y() / p.z() + k.cy;
    if (u < 0.0 || v < 0.0 || u > width - 1.0 || v > height - 1.0) return false;
  }
  return true;
}

std::vector<std::size_t> all_indices(std::size_t n) {
  std::vector<std::size_t> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = i;
  return out;
}

// The normal among `among` with the most of `among` within the angle whose cosine is `cos_off`:
// the direction of the cell's largest plane (a mean would fall between two planes).
Eigen::Vector3f dominant_normal(const std::vector<Eigen::Vector3f>& normals,
                                const std::vector<std::size_t>& among, double cos_off) {
  Eigen::Vector3f best = Eigen::Vector3f::Zero();
  std::size_t best_count = 0;
  for (std::size_t c = 0; c < among.size(); c += 4) {  // every 4th as a candidate suffices
    const Eigen::Vector3f& n = normals[among[c]];
    std::size_t count = 0;
    for (std::size_t i : among) count += normals[i].dot(n) >= cos_off ? 1 : 0;
    if (count > best_count) best_count = count, best = n;
  }
  return best;
}

// Those of `among` farther than the angle from `direction`.
std::vector<std::size_t> off_direction(const std::vector<Eigen::Vector3f>& normals,
                                       const std::vector<std::size_t>& among,
                                       const Eigen::Vector3f& direction, double cos_off) {
  std::vector<std::size_t> out;
  for (std::size_t i : among)
    if (normals[i].dot(direction) < cos_off) out.push_back(i);
  return out;
}

// The RMS distance of `points` from their best plane (through `centroid`): the square root of the
// scatter's least eigenvalue.
double off_plane_rms(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& centroid) {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d d = p.cast<double>() - centroid;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter /
                                                             static_cast<double>(points.size()));
  return std::sqrt(std::max(0.0, eigen.eigenvalues()(0)));
}

}  // namespace

std::vector<Box> user_like_boxes(const PointCloud& frame, const PinholeIntrinsics& intrinsics,
                                 const UserBoxRule& rule) {
  if (!frame.is_organized()) throw Error("user-like boxes: the frame must be organised");
  if (!(rule.box_side > 0.0) || !(rule.voxels_per_side >= 2.0))
    throw Error("user-like boxes: the box side must be positive, with at least 2 voxels across");
  const double leaf = rule.box_side / rule.voxels_per_side;
  // Step 1.
  const PointCloud reduced = downsample_with_normals(frame, leaf, Eigen::Vector3d::Zero());
  // Step 2: cells by their integer coordinates, in a map so that their order is deterministic.
  // Half a box across, so that an object a third of the box wide is a third of its cell.
  const double cell_side = 0.5 * rule.box_side;
  std::map<std::array<int, 3>, Cell> cells;
  for (std::size_t i = 0; i < reduced.size(); ++i) {
    const Eigen::Vector3f& p = reduced.points[i];
    const Eigen::Vector3f& n = reduced.normals[i];
    if (!is_finite(p) || !is_finite(n) || p.z() < rule.min_depth || p.z() > rule.max_depth)
      continue;
    const std::array<int, 3> key{static_cast<int>(std::floor(p.x() / cell_side)),
                                 static_cast<int>(std::floor(p.y() / cell_side)),
                                 static_cast<int>(std::floor(p.z() / cell_side))};
    Cell& cell = cells[key];
    cell.points.push_back(p);
    cell.normals.push_back(n);
  }
  struct Scored {
    double off_both;  ///< fraction of normals off the two dominant directions: rank
    double off_one;   ///< off the dominant one: the structure test
    Eigen::Vector3d centre;
  };
  std::vector<Scored> structured;
  const double cos_off = std::cos(rule.off_plane_angle);
  for (const auto& [key, cell] : cells) {
    if (cell.points.size() < rule.min_cell_points) continue;
    const std::vector<std::size_t> all = all_indices(cell.normals.size());
    const Eigen::Vector3f first = dominant_normal(cell.normals, all, cos_off);
    const std::vector<std::size_t> off_first = off_direction(cell.normals, all, first, cos_off);
    const double off_one = static_cast<double>(off_first.size()) / cell.normals.size();
    if (off_one < rule.min_off_plane) continue;
    const Eigen::Vector3f second = dominant_normal(cell.normals, off_first, cos_off);
    const double off_both =
        static_cast<double>(off_direction(cell.normals, off_first, second, cos_off).size()) /
        cell.normals.size();
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : cell.points) centroid += p.cast<double>();
    centroid /= static_cast<double>(cell.points.size());
    if (off_plane_rms(cell.points, centroid) <= rule.noise.measurement_sigma(centroid.z()))
      continue;  // the normals scatter with the noise of a far, bare surface
    structured.push_back({off_both, off_one, centroid});
  }
  // Steps 3 and 4.
  std::stable_sort(structured.begin(), structured.end(), [](const Scored& a, const Scored& b) {
    return a.off_both != b.off_both ? a.off_both > b.off_both : a.off_one > b.off_one;
  });
  std::vector<Box> boxes;
  for (const Scored& s : structured) {
    if (boxes.size() >= rule.max_boxes) break;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = s.centre;
    const Box box(pose, Eigen::Vector3d::Constant(rule.box_side));
    if (!projects_inside(box, intrinsics, frame.width, frame.height)) continue;
    const bool crowded = std::any_of(boxes.begin(), boxes.end(), [&](const Box& b) {
      return (b.center() - s.centre).norm() < rule.box_side;
    });
    if (!crowded) boxes.push_back(box);
  }
  return boxes;
}

}  // namespace lmk
