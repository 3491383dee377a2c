// lmk gen OUT [--seed S] [--no-noise]: render a synthetic tabletop frame with the simulated Kinect.

#include <cstdio>
#include <memory>

#include "eval/depth_sensor.h"
#include "eval/tabletop_scene.h"
#include "geometry/cloud_io.h"
#include "geometry/pose.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct GenOptions {
  std::string output;
  std::uint64_t seed = 0;
  bool no_noise = false;
};

int run_gen(const GenOptions& options) {
  format_from_path(options.output);  // reject an unknown extension before rendering
  const SyntheticScene scene = make_tabletop_scene(options.seed);
  DepthSensorSettings sensor;
  sensor.seed = options.seed;
  sensor.noise = !options.no_noise;
  const PointCloud cloud = render_depth(scene.mesh, scene.T_world_sensor, sensor);
  write_cloud(options.output, cloud);
  std::printf("wrote %s: %ux%u frame, %zu returns, world frame (z up)\n", options.output.c_str(),
              cloud.width, cloud.height, cloud.count_finite());
  for (const SceneObject& object : scene.objects) {
    const Eigen::Vector3d c = object.box.center();
    const Eigen::Vector3d rpy = rpy_degrees(object.box.pose.linear());
    std::printf("  %-8s centre %7.3f %7.3f %7.3f  yaw %6.1f deg\n", object.name.c_str(), c.x(),
                c.y(), c.z(), rpy.z());
  }
  return kOk;
}

}  // namespace

Subcommand add_gen(CLI::App& app) {
  auto options = std::make_shared<GenOptions>();
  CLI::App* sub = app.add_subcommand(
      "gen", "Render a synthetic tabletop scene (carton, cup, ball) with a simulated Kinect v1");
  sub->add_option("output", options->output, "Cloud file to write (.pcd, .ply, .xyz)")->required();
  sub->add_option("--seed", options->seed, "Scene and noise seed")->capture_default_str();
  sub->add_flag("--no-noise", options->no_noise, "Exact depth: no sensor noise or quantisation");
  return {sub, [options] { return run_gen(*options); }};
}

}  // namespace lmk::cli
