// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/moving_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/datasets/track_sequences.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/objects.h"
#include "lmk/sim/scene_types.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

constexpr double kTableTop = 0.72;
constexpr double kDegree = M_PI / 180.0;

// Where the pushed object may go on the table top (x, y), clear of the clutter behind it.
constexpr double kMinX = -0.35, kMaxX = 0.35, kMinY = -0.25, kMaxY = 0.0;

// A pushed object: its landmark, the object it is a part of, and the part.
struct Pushed {
  const char* landmark;
  ObjectModel (*make)();
  const char* part;
};

ObjectModel bowl() { return make_bowl(); }
ObjectModel cup() { return make_cup(); }
ObjectModel spray() { return make_spray_bottle(); }

const std::vector<Pushed>& pushed_objects() {
  static const std::vector<Pushed> all = {{"bowl", bowl, "bowl"},
                                          {"cup", cup, "cup"},
                                          {"tide_bottle", make_detergent_bottle, "bottle"},
                                          {"spray_bottle", spray, "spray_bottle"}};
  return all;
}

const BenchmarkLandmark& benchmark_landmark(const std::string& name) {
  for (const BenchmarkLandmark& l : benchmark_landmarks())
    if (l.name == name) return l;
  throw Error("moving: no benchmark landmark '" + name + "'");
}

bool on_the_table(const Eigen::Vector2d& xy) {
  return xy.x() >= kMinX && xy.x() <= kMaxX && xy.y() >= kMinY && xy.y() <= kMaxY;
}

// The object's place on the table: where a person's pushes take it.
struct Place {
  Eigen::Vector2d xy;
  double yaw = 0.0;
  Eigen::Isometry3d pose() const {
    return pose_from_xyz_rpy({xy.x(), xy.y(), kTableTop}, {0, 0, yaw});
  }
};

// One frame's push: 0.5-3 cm along a heading that wanders (a hand does not push in straight
// lines), turned back at the edge of the free area; the yaw drifts up to 1.5 degrees a frame and
// stays within 15 degrees of the start, the range the benchmark's scenes place objects in (further
// round, the side the landmark was captured from turns away from the sensor).
class Pusher {
 public:
  Pusher(SplitMix64& rng, Place start) : rng_(rng), start_(start), heading_(uniform(-M_PI, M_PI)) {}

  Place push(Place p) {
    heading_ += uniform(-0.35, 0.35);
    const double step = uniform(0.005, 0.03);
    Eigen::Vector2d next = p.xy + step * Eigen::Vector2d(std::cos(heading_), std::sin(heading_));
    if (!on_the_table(next)) {
      heading_ += M_PI;
      next = p.xy + step * Eigen::Vector2d(std::cos(heading_), std::sin(heading_));
      next = next.cwiseMax(Eigen::Vector2d(kMinX, kMinY)).cwiseMin(Eigen::Vector2d(kMaxX, kMaxY));
    }
    p.xy = next;
    p.yaw = std::clamp(p.yaw + uniform(-1.5, 1.5) * kDegree, start_.yaw - 15 * kDegree,
                       start_.yaw + 15 * kDegree);
    return p;
  }

  // Put down 20-40 cm from where it was lifted, on the free area.
  Place carry(Place p) {
    for (int attempt = 0; attempt < 100; ++attempt) {
      const double angle = uniform(-M_PI, M_PI), distance = uniform(0.2, 0.4);
      const Eigen::Vector2d xy =
          p.xy + distance * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      if (on_the_table(xy)) return {xy, p.yaw};
    }
    // The free area is 70 cm wide: 30 cm along x towards its middle always fits.
    return {p.xy - Eigen::Vector2d(p.xy.x() >= 0.0 ? 0.3 : -0.3, 0.0), p.yaw};
  }

 private:
  double uniform(double lo, double hi) { return lo + (hi - lo) * rng_.uniform01(); }
  SplitMix64& rng_;
  Place start_;
  double heading_;
};

// The table, the floor and wall of the benchmark's scenes, and clutter behind the free area.
TriangleMesh still_world(SplitMix64& rng) {
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform01(); };
  TriangleMesh world;
  world.append(make_box_mesh({6.0, 6.0, 0.02}), pose_from_xyz_rpy({0, 0, -0.01}, {0, 0, 0}));
  world.append(make_box_mesh({6.0, 0.02, 2.5}), pose_from_xyz_rpy({0, 1.5, 1.25}, {0, 0, 0}));
  world.append(make_table({1.2, 0.8, kTableTop}).mesh, Eigen::Isometry3d::Identity());
  for (const double x : {-0.35, 0.0, 0.35}) {
    const Eigen::Vector3d size(uniform(0.06, 0.14), uniform(0.06, 0.12), uniform(0.05, 0.2));
    world.append(make_clutter_box(size).mesh,
                 pose_from_xyz_rpy({x + uniform(-0.08, 0.08), uniform(0.22, 0.3), kTableTop},
                                   {0, 0, uniform(-M_PI, M_PI)}));
  }
  return world;
}

// One sequence's story: where the object is in each frame (nothing while carried), the carry, and
// the camera in each frame.
struct Story {
  std::vector<std::optional<Place>> places;
  Carry carry;
  std::vector<Eigen::Isometry3d> cameras;
};

Story tell_story(SplitMix64& rng, int frames, bool panning) {
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform01(); };
  Story story;
  Place place{{uniform(-0.2, 0.2), uniform(-0.2, -0.05)}, uniform(-15, 15) * kDegree};
  Pusher pusher(rng, place);
  // Carried once, a third to a half of the way through: briefly (1-3 frames, put down elsewhere)
  // or out of view for longer (8-15 frames), alternately by the first push's parity.
  const auto n = static_cast<std::size_t>(frames);
  story.carry.from = n / 3 + static_cast<std::size_t>(uniform(0, 1) * static_cast<double>(n / 6));
  const bool brief = rng.uniform01() < 0.5;
  const std::size_t away = brief ? 1 + rng.uniform_index(3) : 8 + rng.uniform_index(8);
  story.carry.back = std::min(story.carry.from + away, n - 1);
  for (std::size_t f = 0; f < n; ++f) {
    if (f > 0 && f < story.carry.from) place = pusher.push(place);
    if (f == story.carry.from) place = pusher.carry(place);
    if (f > story.carry.back) place = pusher.push(place);
    const bool carried = f >= story.carry.from && f < story.carry.back;
    story.places.push_back(carried ? std::nullopt : std::optional<Place>(place));
  }
  // A head-mounted camera 0.95-1.15 m in front of the table's middle, 1.3 m up; a panning one
  // turns 0.15 degrees a frame about the vertical (4.5 degrees a second), centred on the start.
  const Eigen::Vector3d target(0.0, -0.1, kTableTop);
  const double azimuth = uniform(-0.25, 0.25), distance = uniform(0.95, 1.15);
  const Eigen::Vector3d eye(target.x() + distance * std::sin(azimuth),
                            target.y() - distance * std::cos(azimuth), 1.3 + uniform(-0.08, 0.08));
  const Eigen::Isometry3d camera = camera_look_at(eye, target, Eigen::Vector3d::UnitZ());
  const double rate = (rng.uniform01() < 0.5 ? -1.0 : 1.0) * 0.15 * kDegree;
  for (std::size_t f = 0; f < n; ++f) {
    const double pan =
        panning ? rate * (static_cast<double>(f) - 0.5 * static_cast<double>(n)) : 0.0;
    Eigen::Isometry3d turned = camera;
    turned.linear() = Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) * camera.linear();
    story.cameras.push_back(turned);
  }
  return story;
}

void check(const MovingOptions& o) {
  if (o.seeds < 1 || o.seeds > kMaxSeedsPerType)
    throw Error("gen: --seeds must be 1 to " + std::to_string(kMaxSeedsPerType) + " (got " +
                std::to_string(o.seeds) + ")");
  if (o.frames < 10 || o.frames > kMaxMovingFrames)
    throw Error("gen: --frames must be 10 to " + std::to_string(kMaxMovingFrames) +
                " for the moving preset (got " + std::to_string(o.frames) + ")");
  for (const std::string& name : o.landmarks) {
    const auto& all = moving_landmarks();
    if (std::find(all.begin(), all.end(), name) == all.end())
      throw Error("gen: the moving preset pushes bowl, cup, tide_bottle and spray_bottle, not '" +
                  name + "'");
  }
}

}  // namespace

const std::vector<std::string>& moving_landmarks() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Pushed& p : pushed_objects()) n.push_back(p.landmark);
    return n;
  }();
  return names;
}

Dataset generate_moving_dataset(const std::string& dir, const MovingOptions& options) {
  check(options);
  fs::create_directories(fs::path(dir) / "landmarks");
  fs::create_directories(fs::path(dir) / "scenes");
  std::vector<const Pushed*> chosen;
  for (const Pushed& p : pushed_objects()) {
    if (options.landmarks.empty() ||
        std::count(options.landmarks.begin(), options.landmarks.end(), p.landmark) > 0)
      chosen.push_back(&p);
  }
  Dataset dataset;
  dataset.name = "moving";
  std::vector<TrackSequence> sequences;
  const std::size_t total = chosen.size() * static_cast<std::size_t>(options.seeds) *
                            static_cast<std::size_t>(options.frames);
  std::size_t done = 0;
  for (const Pushed* p : chosen) {
    const BenchmarkLandmark& landmark = benchmark_landmark(p->landmark);
    save_landmark((fs::path(dir) / "landmarks" / (landmark.name + ".lmk")).string(),
                  capture_benchmark_landmark(landmark, options.noise));
    dataset.landmarks.push_back(
        {landmark.name, "landmarks/" + landmark.name + ".lmk", landmark.symmetry});
    const ObjectModel object = p->make();
    for (int k = 0; k < options.seeds; ++k) {
      const std::uint64_t seed = options.first_seed + static_cast<std::uint64_t>(k);
      TrackSequence sequence;
      sequence.name = "moving-" + landmark.name + "-" + std::to_string(seed);
      sequence.landmark = landmark.name;
      SplitMix64 rng(seed * 0x9E3779B97F4A7C15ull ^
                     fnv1a(sequence.name.data(), sequence.name.size()));
      const TriangleMesh still = still_world(rng);
      const Story story = tell_story(rng, options.frames, seed % 2 == 0);
      sequence.carry = story.carry;
      for (std::size_t f = 0; f < story.places.size(); ++f) {
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "-f%04zu", f);
        DatasetScene scene;
        scene.name = sequence.name + suffix;
        scene.file = "scenes/" + scene.name + ".pcd";
        scene.setting = "moving";
        scene.T_scene_sensor = story.cameras[f];
        scene.up = Eigen::Vector3d::UnitZ();
        TriangleMesh world = still;
        DatasetPair pair{landmark.name, true, {}, {}, std::nullopt};
        if (story.places[f]) {
          const Eigen::Isometry3d T_world_object = story.places[f]->pose();
          world.append(object.mesh, T_world_object);
          pair.instances.push_back(object.part(p->part).box.transformed(T_world_object).pose);
        }
        scene.pairs.push_back(pair);
        DepthSensorSettings sensor;
        sensor.noise = options.noise;
        sensor.seed = fnv1a(scene.name.data(), scene.name.size());
        write_cloud((fs::path(dir) / scene.file).string(),
                    render_depth(world, story.cameras[f], sensor));
        sequence.frames.push_back(scene.name);
        dataset.scenes.push_back(std::move(scene));
        if (options.progress) options.progress(++done, total);
      }
      sequences.push_back(std::move(sequence));
    }
  }
  save_dataset(dir, dataset);
  save_track_sequences(dir, dataset, sequences);
  return dataset;
}

}  // namespace lmk
