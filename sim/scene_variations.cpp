// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/scene_variations.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/sensor_models.h"

namespace lmk {

namespace {

// The in-context instances a variation is about, in_context order, each landmark's first `limit`.
std::vector<std::pair<const Landmark*, Box>> in_context_instances(
    const GeneratedScene& scene, const std::map<std::string, Landmark>& captured, int limit) {
  std::vector<std::pair<const Landmark*, Box>> out;
  for (const std::string& name : scene.in_context) {
    const auto model = captured.find(name);
    const auto boxes = scene.instances.find(name);
    if (model == captured.end() || boxes == scene.instances.end()) continue;
    for (int k = 0; k < limit && k < static_cast<int>(boxes->second.size()); ++k)
      out.emplace_back(&model->second, boxes->second[static_cast<std::size_t>(k)]);
  }
  return out;
}

// Whether the segment from `from` to just short of `to` passes through the box (slab method in
// the box's frame).
bool segment_hits_box(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Box& box) {
  const Eigen::Isometry3d T_box_world = box.pose.inverse();
  const Eigen::Vector3d a = T_box_world * from;
  const Eigen::Vector3d d = T_box_world * to - a;
  const double stop = 1.0 - 0.005 / std::max(d.norm(), 1e-9);  // the point's own surface is no hit
  double t0 = 0.0, t1 = stop;
  for (int i = 0; i < 3; ++i) {
    const double half = 0.5 * box.size[i];
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(a[i]) > half) return false;
      continue;
    }
    double lo = (-half - a[i]) / d[i], hi = (half - a[i]) / d[i];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
    if (t0 > t1) return false;
  }
  return true;
}

double share_hidden_by(const Box& occluder, const Eigen::Vector3d& sensor,
                       const std::vector<Eigen::Vector3d>& seen) {
  std::size_t hidden = 0;
  for (const Eigen::Vector3d& p : seen) hidden += segment_hits_box(sensor, p, occluder);
  return seen.empty() ? 0.0 : static_cast<double>(hidden) / static_cast<double>(seen.size());
}

}  // namespace

void view_from_random_viewpoint(GeneratedScene& scene,
                                const std::map<std::string, Landmark>& captured, std::uint64_t seed,
                                const ViewpointRange& range, int attempts) {
  const auto targets = in_context_instances(scene, captured, 1);
  if (targets.empty()) throw Error("scene " + scene.type + " has no in-context instance to view");
  const auto& [landmark, box] = targets.front();
  const Eigen::Vector3d reference = scene.T_world_sensor.translation();
  Eigen::Isometry3d best = scene.T_world_sensor;
  double best_hidden = std::numeric_limits<double>::infinity();
  for (int k = 0; k < std::max(attempts, 1); ++k) {
    scene.T_world_sensor = random_viewpoint(box.pose.translation(), reference,
                                            seed * 0x9E3779B97F4A7C15ull + k, range);
    const double hidden =
        hidden_fraction(*landmark, box, render_scene(scene), sensor_model(scene.sensor).settings);
    if (hidden < best_hidden) best = scene.T_world_sensor, best_hidden = hidden;
    if (hidden <= 0.5) break;
  }
  scene.T_world_sensor = best;
}

void add_occluders(GeneratedScene& scene, const std::map<std::string, Landmark>& captured,
                   std::uint64_t seed, const OcclusionRange& range) {
  SplitMix64 rng(seed ^ 0x0CC1D0E5ull);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform01(); };
  const Eigen::Vector3d sensor = scene.T_world_sensor.translation();
  for (const auto& [landmark, box] :
       in_context_instances(scene, captured, range.max_instances_per_landmark)) {
    // Drawn first, whatever happens next, so that each instance's draws do not depend on another's
    // visibility.
    const double target = uniform(0.0, range.max_hidden);
    const bool touching = rng.uniform01() < range.touching_share;
    const double gap = touching ? uniform(0.0, 0.01) : uniform(0.05, range.max_gap);
    const double thickness = uniform(0.02, 0.06), width = uniform(0.08, 0.25);
    const bool full_height = rng.uniform01() < 0.5;
    const double height_share = uniform(0.4, 0.9), overshoot = uniform(0.02, 0.1);
    const double side = rng.uniform01() < 0.5 ? -1.0 : 1.0;

    const std::vector<char> seen_mask =
        seen_on_instance(*landmark, box, render_scene(scene), sensor_model(scene.sensor).settings);
    const std::vector<Eigen::Vector3d> points = points_on_instance(*landmark, box);
    std::vector<Eigen::Vector3d> seen;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (seen_mask[i]) seen.push_back(points[i]);
    if (seen.empty()) continue;

    // A vertical board facing the sensor across the horizontal line from the instance to it.
    const Eigen::Vector3d centre = box.pose.translation();
    Eigen::Vector3d toward = sensor - centre;
    toward.z() = 0.0;
    if (toward.norm() < 1e-6) continue;  // straight above: no "in front"
    toward.normalize();
    const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(toward);
    double front = 0.0, reach = 0.0, low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Eigen::Vector3d& p : points) {
      front = std::max(front, (p - centre).dot(toward));
      reach = std::max(reach, std::abs((p - centre).dot(across)));
      low = std::min(low, p.z());
      high = std::max(high, p.z());
    }
    const double top = full_height ? high + overshoot : low + (high - low) * height_share;
    const double bottom = std::max(0.0, low - 0.02);
    Box occluder;
    occluder.size = Eigen::Vector3d(width, thickness, std::max(top - bottom, 0.02));
    occluder.pose.linear() << across, toward, Eigen::Vector3d::UnitZ();
    const auto place = [&](double offset) {
      occluder.pose.translation() =
          centre + toward * (front + gap + 0.5 * thickness) + across * (side * offset);
      occluder.pose.translation().z() = bottom + 0.5 * occluder.size.z();
    };
    // Hidden share falls as the board slides sideways; bisect for the drawn share.
    double near = 0.0, far = reach + 0.5 * width + 0.5;
    place(near);
    if (share_hidden_by(occluder, sensor, seen) > target) {
      for (int step = 0; step < 20; ++step) {
        const double mid = 0.5 * (near + far);
        place(mid);
        (share_hidden_by(occluder, sensor, seen) > target ? near : far) = mid;
      }
      place(far);
    }
    scene.mesh.append(make_box_mesh(occluder.size), occluder.pose);
  }
}

}  // namespace lmk
