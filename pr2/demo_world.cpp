#include "pr2/demo_world.h"

#include <algorithm>
#include <cmath>

#include "eval/depth_sensor.h"
#include "geometry/error.h"

namespace lmk {

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
}

void DemoWorld::remove(const std::string& id) {
  const auto it = std::find_if(objects_.begin(), objects_.end(),
                               [&](const PlacedObject& o) { return o.id == id; });
  if (it == objects_.end()) throw Error("demo world: no object '" + id + "'");
  objects_.erase(it);
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

std::optional<Eigen::Isometry3d> DemoWorld::free_patch_near(const std::string& landmark,
                                                            const Box& found) const {
  for (const FreeSurface& surface : surfaces_) {
    if (surface.landmark != landmark) continue;
    // Level the found box onto the surface: keep its place in the surface plane and its heading.
    const Eigen::Vector3d up = surface.top.pose.linear().col(2);
    Eigen::Vector3d heading = found.pose.linear().col(0);
    heading = (heading - heading.dot(up) * up).normalized();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear().col(0) = heading;
    T.linear().col(1) = up.cross(heading);
    T.linear().col(2) = up;
    const Eigen::Vector3d in_surface = surface.top.pose.inverse() * found.center();
    T.translation() = surface.top.pose * Eigen::Vector3d(in_surface.x(), in_surface.y(), 0.0) +
                      surface.box_height * up;
    const Box patch(T, found.size);
    // On the surface: every corner of the patch's footprint is over the top face.
    bool on_surface = true;
    for (const Eigen::Vector3d& corner : patch.corners()) {
      const Eigen::Vector3d c = surface.top.pose.inverse() * corner;
      on_surface = on_surface && std::abs(c.x()) <= 0.5 * surface.top.size.x() &&
                   std::abs(c.y()) <= 0.5 * surface.top.size.y();
    }
    if (!on_surface) continue;
    // Clear: no object's bounding box reaches into the patch box (sampled every centimetre; the
    // surface's own object, which the box stands on, ends below it).
    bool clear = true;
    const Eigen::Vector3i n = (found.size / 0.01).cast<int>().cwiseMax(1);
    for (const PlacedObject& o : objects_) {
      const Box bounds = o.model.bounds.transformed(o.T_base_object);
      for (int i = 0; i <= n.x() && clear; ++i) {
        for (int j = 0; j <= n.y() && clear; ++j) {
          for (int k = 0; k <= n.z() && clear; ++k) {
            const Eigen::Vector3d f(double(i) / n.x() - 0.5, double(j) / n.y() - 0.5,
                                    double(k) / n.z() - 0.5);
            const Eigen::Vector3d p = patch.pose * found.size.cwiseProduct(f);
            // The box's bottom sits just under the surface; only what stands above it counts.
            if ((p - surface.top.pose.translation()).dot(up) > 0.005 && bounds.contains(p))
              clear = false;
          }
        }
      }
    }
    if (clear) return T;
  }
  return std::nullopt;
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
