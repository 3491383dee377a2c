// lmk capture SCENE (--box-center X Y Z --box-rpy R P Y --box-size SX SY SZ | --box-json FILE)
//             --name NAME -o OUT.lmk: cut a landmark out of a scene with a box.

#include <cmath>
#include <cstdio>
#include <memory>

#include "geometry/cloud_io.h"
#include "geometry/error.h"
#include "geometry/pose.h"
#include "landmark/landmark_file.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct CaptureOptions {
  std::string scene, name, output, box_json;
  std::vector<double> center, rpy_deg, size;
  CaptureSettings settings;
};

Box box_from_options(const CaptureOptions& o) {
  if (!o.box_json.empty()) {
    if (!o.center.empty() || !o.size.empty() || !o.rpy_deg.empty()) {
      throw Error("capture: give the box either with --box-json or with --box-center/--box-size");
    }
    return read_box_json(o.box_json);
  }
  if (o.center.empty() || o.size.empty()) {
    throw Error(
        "capture: the box needs --box-center X Y Z and --box-size SX SY SZ (or --box-json)");
  }
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (!o.rpy_deg.empty())
    rpy = Eigen::Vector3d(o.rpy_deg[0], o.rpy_deg[1], o.rpy_deg[2]) * M_PI / 180.0;
  return Box(pose_from_xyz_rpy({o.center[0], o.center[1], o.center[2]}, rpy),
             {o.size[0], o.size[1], o.size[2]});
}

int run_capture(const CaptureOptions& o) {
  format_from_path(o.scene);
  const Box box = box_from_options(o);  // bad box arguments fail before the scene is read
  const PointCloud scene = read_cloud(o.scene);
  const Landmark landmark = capture(scene, box, o.name, o.settings);
  save_landmark(o.output, landmark);
  std::printf("wrote %s: landmark '%s', %zu points, box %.3f x %.3f x %.3f m\n", o.output.c_str(),
              landmark.name.c_str(), landmark.points.size(), box.size.x(), box.size.y(),
              box.size.z());
  return kOk;
}

}  // namespace

Subcommand add_capture(CLI::App& app) {
  auto o = std::make_shared<CaptureOptions>();
  CLI::App* sub = app.add_subcommand("capture", "Cut a landmark out of a scene with a box");
  sub->add_option("scene", o->scene, "Scene cloud (.pcd, .ply, .xyz)")->required();
  sub->add_option("--box-center", o->center, "Box centre in the scene frame, m")->expected(3);
  sub->add_option("--box-rpy", o->rpy_deg, "Box roll pitch yaw, degrees (default 0 0 0)")
      ->expected(3);
  sub->add_option("--box-size", o->size, "Box side lengths, m")->expected(3);
  sub->add_option("--box-json", o->box_json,
                  "Box as JSON {position:[x,y,z], quaternion:[w,x,y,z], size:[sx,sy,sz]}");
  sub->add_option("--name", o->name, "Landmark name")->required();
  sub->add_option("-o,--output", o->output, "Landmark file to write (.lmk)")->required();
  sub->add_option("--leaf", o->settings.leaf_size, "Voxel leaf of the landmark points, m")
      ->capture_default_str();
  sub->add_option("--min-points", o->settings.min_points, "Fewest points a landmark may have")
      ->capture_default_str();
  sub->add_option("--max-box-side", o->settings.max_box_side, "Longest allowed box side, m")
      ->capture_default_str();
  return {sub, [o] { return run_capture(*o); }};
}

}  // namespace lmk::cli
