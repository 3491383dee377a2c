// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/scene_types.h"

#include <cmath>
#include <functional>
#include <initializer_list>

#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/objects.h"
#include "lmk/sim/sensor_models.h"

namespace lmk {
namespace {

const Symmetry kNone{};
const Symmetry kAboutZ{Eigen::Vector3d::UnitZ()};
// A bar handle looks the same turned half a turn about the normal of the face it is mounted on.
const Symmetry kHalfTurnAboutY{Eigen::Vector3d::UnitY(), 2};

// FNV-1a: a scene's random stream must not depend on the standard library's string hash.
std::uint64_t stable_hash(const std::string& text) { return fnv1a(text.data(), text.size()); }

// The generator of one scene: a seeded random stream, the world mesh and its ground truth.
class SceneBuilder {
 public:
  SceneBuilder(const std::string& type, std::uint64_t seed, bool hard)
      : rng_(seed * 0x9E3779B97F4A7C15ull ^ stable_hash(type)), hard_(hard), seed_(seed) {
    scene_.type = type;
    scene_.setting = type.substr(0, type.find('/'));
    // The floor, and a wall 1.5 m behind the origin that bounds the view.
    scene_.mesh.append(make_box_mesh({6.0, 6.0, 0.02}), at({0, 0, -0.01}));
    scene_.mesh.append(make_box_mesh({6.0, 0.02, 2.5}), at({0, 1.5, 1.25}));
  }

  double uniform(double lo, double hi) { return lo + (hi - lo) * rng_.uniform01(); }
  bool hard() const { return hard_; }
  /// Seed 0: the scene the landmarks are captured in.
  bool demonstration() const { return seed_ == 0; }

  // A yaw about z near `nominal`: within 15 degrees, or 60 in hard scenes. Further round, the side
  // a landmark was captured from turns away from the sensor: no method that matches what a sensor
  // saw could find it, and no user would expect one to.
  double yaw(double nominal = 0.0) {
    return nominal + (hard_ ? uniform(-1.05, 1.05) : uniform(-0.26, 0.26));
  }

  static Eigen::Isometry3d at(const Eigen::Vector3d& xyz, double yaw = 0.0) {
    return pose_from_xyz_rpy(xyz, {0, 0, yaw});
  }

  void add(const ObjectModel& object, const Eigen::Isometry3d& T_world_object) {
    scene_.mesh.append(object.mesh, T_world_object);
  }

  void instance(const std::string& landmark, const ObjectModel& object, const std::string& part,
                const Eigen::Isometry3d& T_world_object) {
    scene_.instances[landmark].push_back(object.part(part).box.transformed(T_world_object));
  }

  void in_context(std::vector<std::string> landmarks) { scene_.in_context = std::move(landmarks); }

  // A head-mounted sensor in front of `target` (towards -y), `distance` away and `height` above
  // the floor, with some lateral spread; hard scenes also roll it about its optical axis.
  void look_at(const Eigen::Vector3d& target, double distance, double height) {
    const double azimuth = uniform(-0.25, 0.25) * (hard_ ? 2.0 : 1.0);
    const Eigen::Vector3d eye(target.x() + distance * std::sin(azimuth),
                              target.y() - distance * std::cos(azimuth),
                              height + uniform(-0.08, 0.08));
    Eigen::Isometry3d T = camera_look_at(eye, target, Eigen::Vector3d::UnitZ());
    if (hard_)
      T.linear() =
          T.linear() *
          Eigen::AngleAxisd(uniform(-0.5, 0.5), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    scene_.T_world_sensor = T;
  }

  GeneratedScene take() { return std::move(scene_); }
  Eigen::Vector3d& light() { return scene_.light; }

 private:
  SplitMix64 rng_;
  bool hard_;
  std::uint64_t seed_;
  GeneratedScene scene_;
};

constexpr double kTableTop = 0.72;

// A table at the origin; returns the height of its top.
double add_table(SceneBuilder& b) {
  b.add(make_table({1.2, 0.8, kTableTop}), SceneBuilder::at({0, 0, 0}));
  return kTableTop;
}

// A tabletop object at (x, y) on a surface at height z, with a yaw.
Eigen::Isometry3d on_surface(double x, double y, double z, double yaw) {
  return SceneBuilder::at({x, y, z}, yaw);
}

// Places `object` and records it as an instance of each (landmark, part) listed.
void add_object(SceneBuilder& b, const ObjectModel& object, const Eigen::Isometry3d& T,
                std::initializer_list<std::pair<const char*, const char*>> landmark_parts) {
  b.add(object, T);
  for (const auto& [landmark, part] : landmark_parts) b.instance(landmark, object, part, T);
}

// A bowl, standing alone: an instance of the bowl and of its rim.
void add_bowl(SceneBuilder& b, const Eigen::Isometry3d& T) {
  add_object(b, make_bowl(), T, {{"bowl", "bowl"}, {"bowl_rim", "rim"}});
}

// A stack of `count` nested bowls: only the top one's rim is an instance (the paper's "rim of top
// bowl"); the stack as a whole is no instance of a single bowl.
void add_bowl_stack(SceneBuilder& b, const Eigen::Isometry3d& T_base, int count) {
  const ObjectModel bowl = make_bowl();
  Eigen::Isometry3d T = T_base;
  for (int k = 0; k < count; ++k) {
    T = T_base * SceneBuilder::at({0, 0, 0.018 * k}, b.uniform(-M_PI, M_PI));
    b.add(bowl, T);
  }
  b.instance("bowl_rim", bowl, "rim", T);
}

void add_cup(SceneBuilder& b, const Eigen::Isometry3d& T) {
  add_object(b, make_cup(), T, {{"cup", "cup"}});
}

void add_ball(SceneBuilder& b, const Eigen::Isometry3d& T) {
  add_object(b, make_ball(), T, {{"ball", "ball"}});
}

void add_detergent(SceneBuilder& b, const Eigen::Isometry3d& T) {
  add_object(b, make_detergent_bottle(), T, {{"tide_bottle", "bottle"}});
}

void add_spray(SceneBuilder& b, const Eigen::Isometry3d& T) {
  add_object(b, make_spray_bottle(), T, {{"spray_bottle", "spray_bottle"}, {"spray_top", "top"}});
}

void add_clutter(SceneBuilder& b, double x, double y, double z) {
  const Eigen::Vector3d size(b.uniform(0.06, 0.14), b.uniform(0.06, 0.14), b.uniform(0.05, 0.2));
  b.add(make_clutter_box(size), on_surface(x, y, z, b.uniform(-M_PI, M_PI)));
}

// --- simple -----------------------------------------------------------------------------------

void bowl_and_cup(SceneBuilder& b) {
  const double z = add_table(b);
  add_bowl(b, on_surface(b.uniform(-0.3, -0.15), b.uniform(-0.15, 0.15), z, b.yaw()));
  add_cup(b, on_surface(b.uniform(0.1, 0.3), b.uniform(-0.15, 0.15), z, b.yaw()));
  b.in_context({"bowl", "cup"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

void tide_bottle(SceneBuilder& b) {
  const double z = add_table(b);
  add_detergent(b, on_surface(b.uniform(-0.15, 0.15), b.uniform(-0.1, 0.1), z, b.yaw()));
  b.in_context({"tide_bottle"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

void tide_and_spray(SceneBuilder& b) {
  const double z = add_table(b);
  add_detergent(b, on_surface(b.uniform(-0.35, -0.2), b.uniform(-0.1, 0.1), z, b.yaw()));
  add_spray(b, on_surface(b.uniform(0.15, 0.3), b.uniform(-0.1, 0.1), z, b.yaw()));
  b.in_context({"tide_bottle", "spray_bottle"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

void three_balls(SceneBuilder& b) {
  const double z = add_table(b);
  for (const double x : {-0.3, 0.0, 0.3}) {
    add_ball(b, on_surface(x + b.uniform(-0.05, 0.05), b.uniform(-0.15, 0.15), z, 0.0));
  }
  b.in_context({"ball"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

// --- cluttered --------------------------------------------------------------------------------

void stacked_bowls_and_cup(SceneBuilder& b) {
  const double z = add_table(b);
  add_bowl_stack(b, on_surface(b.uniform(-0.3, -0.15), b.uniform(-0.1, 0.1), z, 0.0), 3);
  add_cup(b, on_surface(b.uniform(0.1, 0.3), b.uniform(-0.1, 0.1), z, b.yaw()));
  b.in_context({"bowl_rim", "cup"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

void shelf(SceneBuilder& b) {
  const ObjectModel shelf = make_shelf();
  b.add(shelf, SceneBuilder::at({0, 0.2, 0}));
  for (const double level : shelf.surfaces) {
    const double side = b.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    add_bowl_stack(b, on_surface(side * b.uniform(0.12, 0.2), 0.2, level, 0.0), 2);
    add_cup(b, on_surface(-side * b.uniform(0.12, 0.22), 0.2, level, b.yaw()));
  }
  b.in_context({"bowl_rim", "cup"});
  b.look_at({0, 0.2, 0.7}, b.uniform(1.25, 1.45), 1.3);
}

void bowls_in_contact(SceneBuilder& b) {
  const double z = add_table(b);
  const double r = make_bowl().bounds.size.x() * 0.5;
  const double x0 = b.uniform(-0.25, -0.1), y0 = b.uniform(-0.1, 0.1);
  for (int k = 0; k < 3; ++k) {
    add_bowl(b, on_surface(x0 + 2.0 * r * k, y0, z, b.uniform(-M_PI, M_PI)));
  }
  // A tennis ball in the middle bowl, on its bottom.
  add_ball(b, on_surface(x0 + 2.0 * r, y0, z, 0.0));
  b.in_context({"bowl_rim", "ball"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

void tide_touching_spray(SceneBuilder& b) {
  const double z = add_table(b);
  const double x = b.uniform(-0.2, 0.0), y = b.uniform(-0.1, 0.1);
  const double bottle_half = 0.5 * make_detergent_bottle().bounds.size.x();
  add_detergent(b, on_surface(x, y, z, 0.0));
  add_spray(b, on_surface(x + bottle_half + 0.04, y, z, b.yaw()));
  b.in_context({"tide_bottle", "spray_top"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

void spray_occluded(SceneBuilder& b) {
  const double z = add_table(b);
  const double x = b.uniform(-0.15, 0.15), y = b.uniform(0.0, 0.15);
  add_spray(b, on_surface(x, y, z, b.yaw()));
  // A box between the sensor and the bottle hides its lower half.
  b.add(make_clutter_box({0.2, 0.06, 0.11}), on_surface(x, y - 0.12, z, 0.0));
  b.in_context({"spray_top"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.25);
}

void spray_with_clutter(SceneBuilder& b) {
  const double z = add_table(b);
  add_spray(b, on_surface(b.uniform(-0.1, 0.1), b.uniform(0.0, 0.1), z, b.yaw()));
  add_ball(b, on_surface(b.uniform(-0.35, -0.25), b.uniform(-0.15, 0.0), z, 0.0));
  add_ball(b, on_surface(b.uniform(0.25, 0.35), b.uniform(-0.15, 0.0), z, 0.0));
  add_clutter(b, b.uniform(-0.45, -0.3), b.uniform(0.1, 0.25), z);
  add_clutter(b, b.uniform(0.3, 0.45), b.uniform(0.1, 0.25), z);
  add_clutter(b, b.uniform(-0.1, 0.1), b.uniform(0.2, 0.3), z);
  b.in_context({"spray_top", "ball"});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

// --- unconventional ---------------------------------------------------------------------------

void chair(SceneBuilder& b, bool lowered) {
  const ObjectModel chair = make_chair(lowered);
  // Rotated chairs were where the paper's method failed: up to 70 degrees in hard scenes (beyond
  // that the sensor sees the backrest edge-on).
  const double yaw = b.hard() ? b.uniform(-1.22, 1.22) : b.uniform(-0.17, 0.17);
  const Eigen::Isometry3d T =
      SceneBuilder::at({b.uniform(-0.1, 0.1), b.uniform(-0.1, 0.1), 0}, yaw);
  b.add(chair, T);
  // The landmark is the left corner. The right one is its mirror image, which no rigid motion
  // makes of it, so it is no instance.
  b.instance("chair_corner", chair, "left_corner", T);
  b.in_context({"chair_corner"});
  b.look_at({0, 0, 0.75}, b.uniform(1.2, 1.4), 1.35);
}

// A wall-mounted object, tilted back by up to 30 degrees in hard scenes.
Eigen::Isometry3d on_wall(SceneBuilder& b, double height) {
  const double tilt = b.hard() ? b.uniform(-0.52, 0.52) : 0.0;
  return pose_from_xyz_rpy({b.uniform(-0.1, 0.1), 0.3, height}, {tilt, 0, b.uniform(-0.1, 0.1)});
}

void tool_rack(SceneBuilder& b, const std::vector<int>& hanging) {
  const ObjectModel rack = make_tool_rack(4, hanging);
  const Eigen::Isometry3d T = on_wall(b, 0.6);
  b.add(rack, T);
  for (const ObjectPart& part : rack.parts) {
    b.instance(part.name.rfind("griple", 0) == 0 ? "griple" : "griple_mount", rack, part.name, T);
  }
  b.in_context({"griple", "griple_mount"});
  b.look_at({0, 0.3, 1.1}, b.uniform(1.0, 1.2), 1.35);
}

void drawer(SceneBuilder& b, bool open) {
  const ObjectModel unit = make_drawer_unit(3, open ? 0 : -1);
  const double yaw = b.hard() ? b.uniform(-0.8, 0.8) : b.uniform(-0.1, 0.1);
  const Eigen::Isometry3d T = SceneBuilder::at({b.uniform(-0.1, 0.1), 0.2, 0}, yaw);
  b.add(unit, T);
  for (const ObjectPart& part : unit.parts) b.instance("drawer_handle", unit, part.name, T);
  b.in_context({"drawer_handle"});
  b.look_at({0, 0.0, 0.45}, b.uniform(1.0, 1.2), 1.3);
}

// --- colour look-alikes (beyond the paper) --------------------------------------------------

const Color kRed{190, 35, 30}, kBlue{35, 70, 180}, kGreen{40, 150, 60}, kYellow{220, 190, 40},
    kWhite{225, 225, 220}, kOrange{230, 120, 30};

// One object of one shape per colour of `paints`, in a row across the table, in an order the seed
// shuffles; each one painted `landmark_paint` is an instance of `landmark`. The demonstration
// (seed 0) keeps the order given, the landmark's colour first. The light is the demonstration's at
// seed 0, else 0.6 to 1.3 times as bright and a few percent warmer or colder per channel.
void colour_row(SceneBuilder& b, const ObjectModel& object, const std::string& landmark,
                const std::string& part, std::vector<Color> paints, const Color& landmark_paint) {
  const double z = add_table(b);
  if (!b.demonstration()) {
    for (std::size_t i = paints.size(); i > 1; --i) {
      std::swap(paints[i - 1], paints[static_cast<std::size_t>(b.uniform(0.0, 1.0) * i) % i]);
    }
    const double gain = b.uniform(0.6, 1.3);
    b.light() = gain * Eigen::Vector3d(b.uniform(0.92, 1.08), 1.0, b.uniform(0.92, 1.08));
  }
  const double spacing = 0.9 / static_cast<double>(paints.size());
  for (std::size_t k = 0; k < paints.size(); ++k) {
    const double x = -0.45 + spacing * (static_cast<double>(k) + 0.5) + b.uniform(-0.02, 0.02);
    const Eigen::Isometry3d T = on_surface(x, b.uniform(-0.12, 0.12), z, b.yaw());
    ObjectModel coloured = object;
    coloured.mesh = painted(object.mesh, paints[k]);
    b.add(coloured, T);
    if (paints[k] == landmark_paint) b.instance(landmark, object, part, T);
  }
  b.in_context({landmark});
  b.look_at({0, 0, z}, b.uniform(0.95, 1.15), 1.3);
}

using Builder = std::function<void(SceneBuilder&)>;
using Builders = std::vector<std::pair<std::string, Builder>>;

const Builders& colour_builders() {
  static const Builders all = {
      {"colour/cups",
       [](SceneBuilder& b) {
         colour_row(b, make_cup(), "red_cup", "cup", {kRed, kBlue, kGreen, kWhite}, kRed);
       }},
      {"colour/bottles",
       [](SceneBuilder& b) {
         colour_row(b, make_detergent_bottle(), "blue_bottle", "bottle", {kBlue, kOrange, kWhite},
                    kBlue);
       }},
      {"colour/cartons",
       [](SceneBuilder& b) {
         colour_row(b, make_carton({0.07, 0.12, 0.18}), "yellow_carton", "carton",
                    {kYellow, kRed, kGreen, kBlue}, kYellow);
       }},
  };
  return all;
}

// The names of `builders`, in order.
std::vector<std::string> names_of(const Builders& builders) {
  std::vector<std::string> out;
  for (const auto& [name, build] : builders) out.push_back(name);
  return out;
}

const Builders& builders() {
  static const Builders all = {
      {"simple/bowl_and_cup", bowl_and_cup},
      {"simple/tide_bottle", tide_bottle},
      {"simple/tide_and_spray", tide_and_spray},
      {"simple/three_balls", three_balls},
      {"cluttered/stacked_bowls_and_cup", stacked_bowls_and_cup},
      {"cluttered/shelf", shelf},
      {"cluttered/bowls_in_contact", bowls_in_contact},
      {"cluttered/tide_touching_spray", tide_touching_spray},
      {"cluttered/spray_occluded", spray_occluded},
      {"cluttered/spray_with_clutter", spray_with_clutter},
      {"unconventional/chair", [](SceneBuilder& b) { chair(b, false); }},
      {"unconventional/lowered_chair", [](SceneBuilder& b) { chair(b, true); }},
      {"unconventional/rack_partly_full",
       [](SceneBuilder& b) {
         tool_rack(b, {0, 2});
       }},
      {"unconventional/rack_full",
       [](SceneBuilder& b) {
         tool_rack(b, {0, 1, 2, 3});
       }},
      {"unconventional/rack_empty", [](SceneBuilder& b) { tool_rack(b, {}); }},
      {"unconventional/drawer", [](SceneBuilder& b) { drawer(b, false); }},
      {"unconventional/drawer_open", [](SceneBuilder& b) { drawer(b, true); }},
  };
  return all;
}

}  // namespace

const std::vector<BenchmarkLandmark>& benchmark_landmarks() {
  static const std::vector<BenchmarkLandmark> all = {
      {"bowl", "simple", "simple/bowl_and_cup", kAboutZ},
      {"cup", "simple", "simple/bowl_and_cup", kNone},
      {"tide_bottle", "simple", "simple/tide_bottle", kNone},
      {"spray_bottle", "simple", "simple/tide_and_spray", kNone},
      {"ball", "simple", "simple/three_balls", kAboutZ},
      {"bowl_rim", "cluttered", "cluttered/stacked_bowls_and_cup", kAboutZ},
      {"spray_top", "cluttered", "cluttered/spray_occluded", kNone},
      {"chair_corner", "unconventional", "unconventional/chair", kNone},
      {"griple", "unconventional", "unconventional/rack_partly_full", kNone},
      {"griple_mount", "unconventional", "unconventional/rack_partly_full", kNone},
      {"drawer_handle", "unconventional", "unconventional/drawer", kHalfTurnAboutY},
  };
  return all;
}

const std::vector<BenchmarkLandmark>& colour_landmarks() {
  // A carton upright looks the same turned half a turn about its vertical axis.
  static const std::vector<BenchmarkLandmark> all = {
      {"red_cup", "colour", "colour/cups", kNone},
      {"blue_bottle", "colour", "colour/bottles", kNone},
      {"yellow_carton", "colour", "colour/cartons", Symmetry{Eigen::Vector3d::UnitZ(), 2}},
  };
  return all;
}

const std::vector<std::string>& colour_scene_types() {
  static const std::vector<std::string> names = names_of(colour_builders());
  return names;
}

const std::vector<std::string>& scene_types() {
  static const std::vector<std::string> names = names_of(builders());
  return names;
}

PointCloud render_scene(const GeneratedScene& scene, bool noise, std::uint64_t noise_seed) {
  DepthSensorSettings sensor = sensor_model(scene.sensor).settings;
  sensor.noise = noise;
  sensor.seed = noise_seed;
  sensor.light = scene.light;
  return render_depth(scene.mesh, scene.T_world_sensor, sensor);
}

GeneratedScene make_scene(const std::string& type, std::uint64_t seed, bool hard) {
  for (const Builders* list : {&builders(), &colour_builders()}) {
    for (const auto& [name, build] : *list) {
      if (name != type) continue;
      SceneBuilder builder(type, seed, hard);
      build(builder);
      return builder.take();
    }
  }
  std::string known;
  for (const std::string& name : scene_types()) known += (known.empty() ? "" : ", ") + name;
  for (const std::string& name : colour_scene_types()) known += ", " + name;
  throw Error("unknown scene type '" + type + "' (known: " + known + ")");
}

}  // namespace lmk
