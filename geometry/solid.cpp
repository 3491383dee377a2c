// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/solid.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "lmk/geometry/error.h"

namespace lmk {

namespace {

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string("solid: the ") + what + " must be positive and finite");
}

// Signed distance to an axis-aligned box of half extents h centred on the origin.
double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& h) {
  const Eigen::Vector3d q = p.cwiseAbs() - h;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;
}

// Signed distance to a cylinder about z of radius r and half length h, centred on the origin.
double cylinder_distance(const Eigen::Vector3d& p, double r, double h) {
  const Eigen::Vector2d q(p.head<2>().norm() - r, std::abs(p.z()) - h);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// n evenly spread values over [-half, half], at least 2 (both ends) when half > 0.
std::vector<double> spread(double half, double spacing) {
  const int n = std::max(2, static_cast<int>(std::ceil(2.0 * half / spacing)) + 1);
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = -half + 2.0 * half * i / (n - 1);
  return v;
}

std::vector<Eigen::Vector3d> box_surface(const Eigen::Vector3d& h, double spacing) {
  std::vector<Eigen::Vector3d> out;
  const std::vector<double> xs = spread(h.x(), spacing), ys = spread(h.y(), spacing),
                            zs = spread(h.z(), spacing);
  // Each face's grid; edges and corners appear on two or three faces, which costs nothing.
  for (double s : {-1.0, 1.0}) {
    for (double y : ys)
      for (double z : zs) out.emplace_back(s * h.x(), y, z);
    for (double x : xs)
      for (double z : zs) out.emplace_back(x, s * h.y(), z);
    for (double x : xs)
      for (double y : ys) out.emplace_back(x, y, s * h.z());
  }
  return out;
}

// Points on a circle of radius r at height z, and, when `filled`, on smaller rings inside it.
void add_disc(std::vector<Eigen::Vector3d>& out, double r, double z, double spacing, bool filled) {
  const int rings = filled ? std::max(1, static_cast<int>(std::ceil(r / spacing))) : 1;
  for (int k = rings; k >= 1; --k) {
    const double rk = r * k / rings;
    const int n = std::max(6, static_cast<int>(std::ceil(2.0 * M_PI * rk / spacing)));
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      out.emplace_back(rk * std::cos(a), rk * std::sin(a), z);
    }
  }
  if (filled) out.emplace_back(0.0, 0.0, z);
}

std::vector<Eigen::Vector3d> cylinder_surface(double r, double h, double spacing) {
  std::vector<Eigen::Vector3d> out;
  for (double z : spread(h, spacing)) add_disc(out, r, z, spacing, false);
  add_disc(out, r, -h, spacing, true);
  add_disc(out, r, h, spacing, true);
  return out;
}

std::vector<Eigen::Vector3d> sphere_surface(double r, double spacing) {
  // Rings of latitude, each spread by its own circumference.
  std::vector<Eigen::Vector3d> out;
  const int rings = std::max(2, static_cast<int>(std::ceil(M_PI * r / spacing)));
  for (int i = 0; i <= rings; ++i) {
    const double polar = M_PI * i / rings;
    const double ring = r * std::sin(polar);
    const int n = std::max(1, static_cast<int>(std::ceil(2.0 * M_PI * ring / spacing)));
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * M_PI * k / n;
      out.emplace_back(ring * std::cos(a), ring * std::sin(a), r * std::cos(polar));
    }
  }
  return out;
}

}  // namespace

Solid Solid::box(const Eigen::Vector3d& size) {
  for (int i = 0; i < 3; ++i) require_positive(size[i], "box's size");
  return Solid(Kind::box, size);
}

Solid Solid::cylinder(double radius, double length) {
  require_positive(radius, "cylinder's radius");
  require_positive(length, "cylinder's length");
  return Solid(Kind::cylinder, Eigen::Vector3d(radius, radius, length));
}

Solid Solid::sphere(double radius) {
  require_positive(radius, "sphere's radius");
  return Solid(Kind::sphere, Eigen::Vector3d::Constant(radius));
}

double Solid::signed_distance(const Eigen::Vector3d& p) const {
  switch (kind_) {
    case Kind::box:
      return box_distance(p, 0.5 * size_);
    case Kind::cylinder:
      return cylinder_distance(p, size_.x(), 0.5 * size_.z());
    case Kind::sphere:
      break;
  }
  return p.norm() - size_.x();
}

double Solid::bounding_radius() const {
  switch (kind_) {
    case Kind::box:
      return 0.5 * size_.norm();
    case Kind::cylinder:
      return std::hypot(size_.x(), 0.5 * size_.z());
    case Kind::sphere:
      break;
  }
  return size_.x();
}

std::vector<Eigen::Vector3d> Solid::surface_points(double spacing) const {
  require_positive(spacing, "spacing of surface points");
  switch (kind_) {
    case Kind::box:
      return box_surface(0.5 * size_, spacing);
    case Kind::cylinder:
      return cylinder_surface(size_.x(), 0.5 * size_.z(), spacing);
    case Kind::sphere:
      break;
  }
  return sphere_surface(size_.x(), spacing);
}

std::vector<CoveringSphere> cover_with_spheres(const std::vector<Eigen::Vector3d>& points,
                                               double cell) {
  require_positive(cell, "covering spheres' cell");
  // Each cell's points' bounding box, in a sorted map for an order independent of the input's.
  std::map<std::tuple<long, long, long>, Eigen::AlignedBox3d> cells;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d c = (p / cell).array().floor();
    cells[{static_cast<long>(c.x()), static_cast<long>(c.y()), static_cast<long>(c.z())}].extend(p);
  }
  std::vector<CoveringSphere> out;
  out.reserve(cells.size());
  for (const auto& [key, bounds] : cells) {
    // A sphere no smaller than a millimetre: a lone vertex is a point of the surface all the same.
    out.push_back({bounds.center(), std::max(0.5 * bounds.diagonal().norm(), 1e-3)});
  }
  return out;
}

}  // namespace lmk
