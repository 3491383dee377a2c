#include "eval/depth_sensor.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "eval/detail/mesh_tree.h"
#include "geometry/error.h"
#include "geometry/random.h"

namespace lmk {
namespace {

using detail::Kernel;
using detail::to_cgal;

// Kinect v1 depth degradation: Gaussian axial noise growing with depth squared (Khoshelham &
// Elberink 2012), then quantisation of the disparity from which the sensor triangulates depth.
double degrade_depth(double z, const DepthSensorSettings& s, SplitMix64& rng) {
  const double sigma = s.noise_a + s.noise_b * (z - s.noise_z0) * (z - s.noise_z0);
  const double noisy = z + sigma * rng.normal();
  const double disparity = s.fx * s.baseline / noisy;
  const double quantised = std::round(disparity / s.disparity_step) * s.disparity_step;
  return s.fx * s.baseline / quantised;
}

}  // namespace

PointCloud render_depth(const TriangleMesh& world, const Eigen::Isometry3d& T_world_sensor,
                        const DepthSensorSettings& s) {
  if (s.width <= 0 || s.height <= 0 || !(s.fx > 0) || !(s.fy > 0) || !(s.min_range > 0) ||
      !(s.max_range > s.min_range)) {
    throw Error(
        "render_depth: image size, focal lengths and range must be positive, "
        "with max_range > min_range");
  }
  const detail::MeshTree mesh_tree(world);
  const detail::AabbTree& tree = mesh_tree.tree;

  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(s.width);
  cloud.height = static_cast<std::uint32_t>(s.height);
  cloud.points.assign(static_cast<std::size_t>(s.width) * s.height,
                      Eigen::Vector3f::Constant(std::nanf("")));
  cloud.T_cloud_sensor = T_world_sensor;
  if (mesh_tree.triangles.empty()) return cloud;

  const Eigen::Vector3d origin = T_world_sensor.translation();
  const double cos_max_incidence = std::cos(s.max_incidence);
  tbb::parallel_for(0, s.height, [&](int v) {
    for (int u = 0; u < s.width; ++u) {
      const Eigen::Vector3d ray_sensor((u - s.cx) / s.fx, (v - s.cy) / s.fy, 1.0);
      const Eigen::Vector3d direction = T_world_sensor.linear() * ray_sensor;
      const auto hit =
          tree.first_intersection(Kernel::Ray_3(to_cgal(origin), to_cgal(origin + direction)));
      if (!hit) continue;
      const Kernel::Point_3* point = boost::get<Kernel::Point_3>(&hit->first);
      if (point == nullptr) continue;  // the ray runs inside a triangle's plane: grazing
      const Eigen::Vector3d p(point->x(), point->y(), point->z());
      const double z = (T_world_sensor.linear().transpose() * (p - origin)).z();
      if (z < s.min_range || z > s.max_range) continue;
      const detail::Triangle& tri = *hit->second;
      const Kernel::Vector_3 n = CGAL::cross_product(tri[1] - tri[0], tri[2] - tri[0]);
      const Eigen::Vector3d normal = Eigen::Vector3d(n.x(), n.y(), n.z()).normalized();
      if (std::abs(normal.dot(direction.normalized())) < cos_max_incidence) continue;
      const std::size_t index = static_cast<std::size_t>(v) * s.width + u;
      double depth = z;
      if (s.noise) {
        // One stream per pixel, so the noise does not depend on which thread renders which row.
        SplitMix64 rng(s.seed ^ (0x9e3779b97f4a7c15ULL * (index + 1)));
        depth = degrade_depth(z, s, rng);
      }
      cloud.points[index] = (origin + direction * depth).cast<float>();  // ray_sensor.z() == 1
    }
  });
  return cloud;
}

}  // namespace lmk
