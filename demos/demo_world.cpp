// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/demos/demo_world.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk {

namespace {

// Revisions are drawn from one sequence for the whole process, so that two worlds built apart
// never share one.
std::uint64_t next_revision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

void DemoWorld::add(std::string id, ObjectModel model, const Eigen::Isometry3d& T_base_object,
                    std::vector<std::pair<std::string, std::string>> landmarks) {
  if (object(id)) throw Error("demo world: object '" + id + "' twice");
  for (const auto& [landmark, part] : landmarks) model.part(part);  // throws for an unknown part
  PlacedObject o;
  o.id = std::move(id);
  o.model = std::move(model);
  o.T_base_object = T_base_object;
  o.landmarks = std::move(landmarks);
  objects_.push_back(std::move(o));
  revision_ = next_revision();
}

void DemoWorld::remove(const std::string& id) {
  const auto it = std::find_if(objects_.begin(), objects_.end(),
                               [&](const PlacedObject& o) { return o.id == id; });
  if (it == objects_.end()) throw Error("demo world: no object '" + id + "'");
  objects_.erase(it);
  revision_ = next_revision();
}

void DemoWorld::hide_under(const std::string& id, const std::string& by) {
  for (PlacedObject& o : objects_) {
    if (o.id == id) {
      o.hidden_by = by;
      return;
    }
  }
  throw Error("demo world: no object '" + id + "'");
}

const PlacedObject* DemoWorld::object(const std::string& id) const {
  for (const PlacedObject& o : objects_) {
    if (o.id == id) return &o;
  }
  return nullptr;
}

std::vector<std::pair<Box, std::string>> DemoWorld::instances(const std::string& landmark) const {
  std::vector<std::pair<Box, std::string>> out;
  for (const PlacedObject& o : objects_) {
    if (!o.hidden_by.empty() && object(o.hidden_by)) continue;
    for (const auto& [name, part] : o.landmarks) {
      if (name == landmark)
        out.emplace_back(o.model.part(part).box.transformed(o.T_base_object), o.id);
    }
  }
  return out;
}

bool DemoWorld::has_free_surface(const std::string& landmark) const {
  return std::any_of(surfaces_.begin(), surfaces_.end(),
                     [&](const FreeSurface& s) { return s.landmark == landmark; });
}

namespace {

// Points on every triangle of `mesh`, at most `spacing` apart along its edges.
std::vector<Eigen::Vector3d> surface_samples(const TriangleMesh& mesh, double spacing) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices[t.x()], &b = mesh.vertices[t.y()],
                          &c = mesh.vertices[t.z()];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        out.push_back(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
      }
    }
  }
  return out;
}

}  // namespace

std::optional<Eigen::Isometry3d> DemoWorld::free_patch_near(const std::string& landmark,
                                                            const Box& found) const {
  constexpr double kStep = 0.005, kReach = 0.03;  // search the nearest valid place within 3 cm
  std::vector<Eigen::Vector3d> obstacles;
  for (const PlacedObject& o : objects_) {
    for (const Eigen::Vector3d& p : surface_samples(o.model.mesh, 0.005)) {
      obstacles.push_back(o.T_base_object * p);
    }
  }
  std::optional<Eigen::Isometry3d> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const FreeSurface& surface : surfaces_) {
    if (surface.landmark != landmark) continue;
    // Level the found box onto the surface: keep its place in the surface plane and its heading.
    const Eigen::Vector3d up = surface.top.pose.linear().col(2);
    Eigen::Vector3d heading = found.pose.linear().col(0);
    heading = (heading - heading.dot(up) * up).normalized();
    Eigen::Isometry3d levelled = Eigen::Isometry3d::Identity();
    levelled.linear().col(0) = heading;
    levelled.linear().col(1) = up.cross(heading);
    levelled.linear().col(2) = up;
    const Eigen::Vector3d in_surface = surface.top.pose.inverse() * found.center();
    levelled.translation() =
        surface.top.pose * Eigen::Vector3d(in_surface.x(), in_surface.y(), 0.0) +
        surface.box_height * up;
    const Eigen::Vector3d half = 0.5 * found.size;
    // Only what stands on the surface (the box's bottom sits just under it, on the patch itself)
    // and near enough to reach into a shifted box can block it.
    std::vector<Eigen::Vector3d> near;
    const double radius = half.norm() + kReach;
    for (const Eigen::Vector3d& p : obstacles) {
      if ((p - surface.top.pose.translation()).dot(up) > 0.005 &&
          (p - levelled.translation()).norm() <= radius) {
        near.push_back(p);
      }
    }
    const int n = static_cast<int>(std::round(kReach / kStep));
    for (int i = -n; i <= n; ++i) {
      for (int j = -n; j <= n; ++j) {
        const Eigen::Vector3d shift(i * kStep, j * kStep, 0.0);
        if (shift.norm() > kReach || shift.norm() >= best_distance) continue;
        Eigen::Isometry3d T = levelled;
        T.translation() += levelled.linear() * shift;
        // On the surface: every corner of the patch's footprint is over the top face.
        bool valid = true;
        for (const Eigen::Vector3d& corner : Box(T, found.size).corners()) {
          const Eigen::Vector3d c = surface.top.pose.inverse() * corner;
          valid = valid && std::abs(c.x()) <= 0.5 * surface.top.size.x() &&
                  std::abs(c.y()) <= 0.5 * surface.top.size.y();
        }
        // Clear: no object's surface inside the box.
        const Eigen::Isometry3d T_patch_base = T.inverse();
        for (std::size_t k = 0; k < near.size() && valid; ++k) {
          if (((T_patch_base * near[k]).cwiseAbs() - half).maxCoeff() <= 0.0) valid = false;
        }
        if (valid) {
          best = T;
          best_distance = shift.norm();
        }
      }
    }
  }
  return best;
}

TriangleMesh DemoWorld::mesh() const {
  TriangleMesh world;
  Eigen::Isometry3d floor = Eigen::Isometry3d::Identity();
  floor.translation() = Eigen::Vector3d(0, 0, kFloorInBase - 0.01);
  world.append(make_box_mesh({8.0, 8.0, 0.02}), floor);
  for (const PlacedObject& o : objects_) world.append(o.model.mesh, o.T_base_object);
  return world;
}

PointCloud DemoWorld::observe(const Eigen::Isometry3d& T_base_sensor, std::uint64_t seed) const {
  DepthSensorSettings settings;
  settings.seed = seed;
  return render_depth(mesh(), T_base_sensor, settings);
}

}  // namespace lmk
