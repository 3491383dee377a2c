// SPDX-License-Identifier: BSD-3-Clause
// lmk robot info | fk | ik: the PR2's groups, forward and inverse kinematics. Every pose is the
// group's tool frame in base_link, for the torso height given by --torso (m, default 0).

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/json/pose_json.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct RobotOptions {
  std::string urdf, group = "right_arm";
  double torso = 0.0;
  std::vector<double> joints, position, rpy_deg, seed;
  bool json = false;
};

Pr2Kinematics make_kinematics(const RobotOptions& o) {
  return Pr2Kinematics(o.urdf.empty() ? RobotModel::pr2() : RobotModel::from_file(o.urdf), o.torso);
}

GroupInfo require_group(const Pr2Kinematics& k, const std::string& name) {
  if (const auto g = k.group(name)) return *g;
  std::string known;
  for (const auto& g : k.groups()) known += (known.empty() ? "" : ", ") + g;
  throw Error("unknown group '" + name + "' (groups: " + known + ")");
}

void print_pose(const Eigen::Isometry3d& T, bool json) {
  if (json) {
    std::cout << detail::pose_to_json(T).dump() << "\n";
    return;
  }
  const Eigen::Vector3d p = T.translation();
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d rpy = rpy_degrees(T.linear());
  std::printf("position    %.6f %.6f %.6f m\n", p.x(), p.y(), p.z());
  std::printf("quaternion  %.6f %.6f %.6f %.6f (w x y z)\n", q.w(), q.x(), q.y(), q.z());
  std::printf("rpy         %.3f %.3f %.3f deg\n", rpy.x(), rpy.y(), rpy.z());
}

int run_info(const RobotOptions& o) {
  const Pr2Kinematics k = make_kinematics(o);
  std::printf("torso height %.3f m; poses are tool frames in base_link\n", o.torso);
  for (const std::string& name : k.groups()) {
    const GroupInfo g = *k.group(name);
    std::printf("\n%s: %s -> %s, %zu joints\n", g.name.c_str(), g.root_link.c_str(),
                g.tip_link.c_str(), g.joints.size());
    for (const JointInfo& j : g.joints) {
      if (j.continuous()) {
        std::printf("  %-26s continuous %24s  %.3f /s\n", j.name.c_str(), "", j.max_velocity);
      } else {
        std::printf("  %-26s %-10s [%9.4f, %9.4f]  %.3f /s\n", j.name.c_str(), j.type.c_str(),
                    j.lower, j.upper, j.max_velocity);
      }
    }
  }
  return kOk;
}

int run_fk(const RobotOptions& o) {
  const Pr2Kinematics k = make_kinematics(o);
  require_group(k, o.group);
  Eigen::Isometry3d T;
  const CallResult r = k.forward(o.group, o.joints, T);
  if (!r.ok()) throw Error("fk: " + r.message);
  print_pose(T, o.json);
  return kOk;
}

int run_ik(const RobotOptions& o) {
  const Pr2Kinematics k = make_kinematics(o);
  const GroupInfo g = require_group(k, o.group);
  if (!o.seed.empty() && o.seed.size() != g.joints.size()) {
    throw Error("ik: --seed has " + std::to_string(o.seed.size()) + " values; group '" + g.name +
                "' has " + std::to_string(g.joints.size()) + " joints");
  }
  const Eigen::Vector3d rpy =
      Eigen::Vector3d(o.rpy_deg[0], o.rpy_deg[1], o.rpy_deg[2]) * M_PI / 180.0;
  const Eigen::Isometry3d target =
      pose_from_xyz_rpy({o.position[0], o.position[1], o.position[2]}, rpy);
  const IkResult r = k.inverse(o.group, target, o.seed);
  if (!r.success) {
    if (r.failure == IkFailure::kBadRequest) throw Error("ik: " + r.message);
    std::fprintf(stderr, "lmk: unreachable: %s\n", r.message.c_str());
    return kInternalError;  // exit 1: a valid request the robot cannot do
  }
  if (o.json) {
    std::cout << nlohmann::json{{"joints", r.joints},
                                {"position_error_m", r.position_error},
                                {"rotation_error_rad", r.rotation_error}}
                     .dump()
              << "\n";
    return kOk;
  }
  for (std::size_t i = 0; i < r.joints.size(); ++i) {
    std::printf("%-26s %10.6f\n", g.joints[i].name.c_str(), r.joints[i]);
  }
  std::printf("position error  %.2e m, rotation error %.2e rad\n", r.position_error,
              r.rotation_error);
  return kOk;
}

void add_common(CLI::App* sub, RobotOptions& o) {
  sub->add_option("--urdf", o.urdf, "Robot description (default: lmk's PR2)");
  sub->add_option("--torso", o.torso, "Torso height, m (0 to 0.33)")->capture_default_str();
}

}  // namespace

Subcommand add_robot(CLI::App& app) {
  auto o = std::make_shared<RobotOptions>();
  CLI::App* sub = app.add_subcommand("robot", "PR2 model: groups, forward and inverse kinematics");
  sub->require_subcommand(1);
  CLI::App* info = sub->add_subcommand("info", "Groups, joints and limits");
  add_common(info, *o);
  CLI::App* fk = sub->add_subcommand("fk", "Tool pose in base_link for joint values");
  add_common(fk, *o);
  fk->add_option("--group", o->group, "left_arm, right_arm or head")->capture_default_str();
  fk->add_option("--joints", o->joints, "Joint values in the group's order, rad or m")
      ->required()
      ->check(finite_number());
  fk->add_flag("--json", o->json, "Print {\"position\":[x,y,z],\"quaternion\":[w,x,y,z]}");
  CLI::App* ik = sub->add_subcommand("ik", "Joint values that put the tool at a pose in base_link");
  add_common(ik, *o);
  ik->add_option("--group", o->group, "left_arm or right_arm")->capture_default_str();
  ik->add_option("--position", o->position, "Tool position X Y Z, m")
      ->expected(3)
      ->required()
      ->check(finite_number());
  ik->add_option("--rpy", o->rpy_deg, "Tool roll pitch yaw, degrees")
      ->expected(3)
      ->required()
      ->check(finite_number());
  ik->add_option("--seed", o->seed,
                 "Joint values to start from (the nearest solution is preferred)")
      ->check(finite_number());
  ik->add_flag("--json", o->json,
               "Print {\"joints\":[...],\"position_error_m\":e,\"rotation_error_rad\":e}");
  return {sub, [o, info, fk] {
            if (info->parsed()) return run_info(*o);
            if (fk->parsed()) return run_fk(*o);
            return run_ik(*o);
          }};
}

}  // namespace lmk::cli
