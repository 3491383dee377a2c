// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/depth_sensor.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"
#include "lmk/sim/detail/mesh_tree.h"

namespace lmk {
namespace {

using detail::Kernel;
using detail::to_cgal;

// Independent per-pixel streams for the noise and the flying pixels, so that a frame does not
// depend on which thread renders which row.
constexpr std::uint64_t kNoiseStream = 0;
constexpr std::uint64_t kFlyingPixelStream = 0x5bd1e9955bd1e995ULL;
constexpr std::uint64_t kColourStream = 0xc2b2ae3d27d4eb4fULL;

// The colour a pixel records of a painted surface: its paint times the light's gain per channel,
// shaded by how squarely the light (near the camera, plus the room's ambient light) meets it, with
// the colour camera's noise. `facing` is |cos| of the angle between the ray and the normal.
Color shaded_colour(const Color& paint, double facing, SplitMix64 rng,
                    const DepthSensorSettings& s) {
  const double shade = 0.45 + 0.55 * facing;
  const auto channel = [&](std::uint8_t base, double gain) {
    const double v = base * gain * shade + s.colour_noise * rng.normal();
    return static_cast<std::uint8_t>(std::clamp(std::round(v), 0.0, 255.0));
  };
  return {channel(paint.r, s.light.x()), channel(paint.g, s.light.y()),
          channel(paint.b, s.light.z())};
}

SplitMix64 pixel_stream(std::uint64_t seed, std::size_t pixel, std::uint64_t stream) {
  return SplitMix64(seed ^ stream ^ (0x9e3779b97f4a7c15ULL * (pixel + 1)));
}

// Whether a ray certainly misses a triangle: a cheap test (Moller & Trumbore 1997) that lets the
// tree's search skip the triangle instead of constructing CGAL's intersection with it, a quarter
// of the time a frame takes. Only clear misses are skipped: by a margin far above the rounding of
// either computation, and never for a ray (nearly) in the triangle's plane or a sliver triangle,
// so the first intersection found, and every rendered frame, stays exactly CGAL's.
class CertainMiss {
 public:
  CertainMiss(const Eigen::Vector3d& from, const Eigen::Vector3d& towards)
      : origin_(from), direction_(towards - from), direction_norm2_(direction_.squaredNorm()) {}

  bool operator()(const detail::TriangleIterator& triangle) const {
    const auto vertex = [&](int i) {
      const Kernel::Point_3& corner = triangle->vertex(i);
      return Eigen::Vector3d(corner.x(), corner.y(), corner.z());
    };
    const Eigen::Vector3d a = vertex(0), e1 = vertex(1) - a, e2 = vertex(2) - a;
    const Eigen::Vector3d p = direction_.cross(e2);
    const double det = e1.dot(p);
    // Near-parallel ray or sliver triangle: the barycentric coordinates below are ill-conditioned.
    // Compared squared: no square root per triangle on this, the renderer's hottest path.
    if (!(det * det >
          kParallel * kParallel * e1.squaredNorm() * e2.squaredNorm() * direction_norm2_)) {
      return false;
    }
    const Eigen::Vector3d s = origin_ - a;
    const double u = s.dot(p) / det;
    if (u < -kMargin || u > 1.0 + kMargin) return true;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = direction_.dot(q) / det;
    if (v < -kMargin || u + v > 1.0 + kMargin) return true;
    return e2.dot(q) / det < -kMargin;  // behind the ray's source
  }

 private:
  // det / (|e1| |e2| |d|): the sine of the triangle's angle at its first vertex times that of the
  // ray's angle to the triangle's plane. Above 1e-4 the coordinates' rounding stays below 1e-9.
  static constexpr double kParallel = 1e-4;
  static constexpr double kMargin = 1e-6;  // in barycentric units, and in ray lengths behind it
  Eigen::Vector3d origin_, direction_;
  double direction_norm2_;  // the same for every triangle the ray is tested against
};

// The first surface along the ray from `from` through `towards`, if any.
std::optional<std::pair<Eigen::Vector3d, const detail::Triangle*>> first_hit(
    const detail::AabbTree& tree, const Eigen::Vector3d& from, const Eigen::Vector3d& towards) {
  const auto hit = tree.first_intersection(Kernel::Ray_3(to_cgal(from), to_cgal(towards)),
                                           CertainMiss(from, towards));
  if (!hit) return std::nullopt;
  const Kernel::Point_3* point = boost::get<Kernel::Point_3>(&hit->first);
  if (point == nullptr) return std::nullopt;  // the ray runs inside a triangle's plane: grazing
  return std::make_pair(Eigen::Vector3d(point->x(), point->y(), point->z()), &*hit->second);
}

// Flying pixels: a pixel on a depth edge sees both surfaces and may return a depth between them.
// Reads the exact depths `z` (NaN: no return) and writes the mixed ones into `out`.
void add_flying_pixels(const std::vector<double>& z, const DepthSensorSettings& s,
                       std::vector<double>& out) {
  tbb::parallel_for(0, s.height, [&](int v) {
    for (int u = 0; u < s.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * s.width + u;
      if (std::isnan(z[i])) continue;
      double other = z[i];
      const int du[4] = {-1, 1, 0, 0}, dv[4] = {0, 0, -1, 1};
      for (int k = 0; k < 4; ++k) {
        const int nu = u + du[k], nv = v + dv[k];
        if (nu < 0 || nv < 0 || nu >= s.width || nv >= s.height) continue;
        const double zn = z[static_cast<std::size_t>(nv) * s.width + nu];
        if (std::abs(zn - z[i]) > std::max(s.edge_jump * z[i], std::abs(other - z[i]))) other = zn;
      }
      if (other == z[i]) continue;
      SplitMix64 rng = pixel_stream(s.seed, i, kFlyingPixelStream);
      if (rng.uniform01() < s.flying_pixel_rate) out[i] = z[i] + rng.uniform01() * (other - z[i]);
    }
  });
}

}  // namespace

std::vector<double> sensor_noise_field(const DepthSensorSettings& s) {
  const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
  std::vector<double> white(pixels);
  for (std::size_t i = 0; i < pixels; ++i)
    white[i] = pixel_stream(s.seed, i, kNoiseStream).normal();
  if (s.noise_window <= 1) return white;
  // A box filter over the window, rescaled by the square root of the pixels it averaged, so that
  // every pixel keeps unit variance while its neighbours share part of it.
  const int r = s.noise_window / 2;
  std::vector<double> field(pixels);
  tbb::parallel_for(0, s.height, [&](int v) {
    for (int u = 0; u < s.width; ++u) {
      double sum = 0.0;
      int n = 0;
      for (int dv = -r; dv <= r; ++dv) {
        for (int du = -r; du <= r; ++du) {
          const int nu = u + du, nv = v + dv;
          if (nu < 0 || nv < 0 || nu >= s.width || nv >= s.height) continue;
          sum += white[static_cast<std::size_t>(nv) * s.width + nu];
          ++n;
        }
      }
      field[static_cast<std::size_t>(v) * s.width + u] = sum / std::sqrt(static_cast<double>(n));
    }
  });
  return field;
}

double sensor_depth(double z, double unit_noise, const DepthSensorSettings& s) {
  // Gaussian axial noise growing with depth squared (Khoshelham & Elberink 2012), then the
  // quantisation of the disparity from which the sensor triangulates depth, then millimetres.
  const double sigma = s.noise_a + s.noise_b * (z - s.noise_z0) * (z - s.noise_z0);
  const double noisy = z + sigma * unit_noise;
  // A time-of-flight camera measures no disparity (disparity_step 0): no levels.
  const double fb = s.disparity_focal * s.baseline;
  const double depth = s.disparity_step > 0.0
                           ? fb / (std::round(fb / noisy / s.disparity_step) * s.disparity_step)
                           : noisy;
  return s.depth_unit > 0.0 ? std::round(depth / s.depth_unit) * s.depth_unit : depth;
}

double depth_level_spacing(double z, const DepthSensorSettings& s) {
  return s.disparity_step * z * z / (s.disparity_focal * s.baseline);
}

namespace {

// lmk::Error unless the sensor's settings can render an image.
void check_sensor_settings(const DepthSensorSettings& s) {
  if (s.width <= 0 || s.height <= 0 || !(s.fx > 0) || !(s.fy > 0) || !(s.min_range > 0) ||
      !(s.max_range > s.min_range) || !(s.disparity_focal > 0) || !(s.baseline > 0) ||
      !(s.disparity_step >= 0) || !(s.depth_unit >= 0) ||
      !(s.flying_pixel_rate >= 0 && s.flying_pixel_rate <= 1) || !(s.edge_jump > 0) ||
      s.noise_window < 1 || s.noise_window % 2 == 0) {
    throw Error(
        "render_depth: image size, focal lengths, range, baseline, disparity step and edge jump "
        "must be positive, with max_range > min_range, the depth unit non-negative and the "
        "flying-pixel rate in [0, 1], and the noise window odd");
  }
}

// Pixel (u, v)'s ray in the world frame, with unit depth along the optical axis.
Eigen::Vector3d pixel_ray(const Eigen::Isometry3d& T_world_sensor, const DepthSensorSettings& s,
                          int u, int v) {
  return Eigen::Vector3d(T_world_sensor.linear() *
                         Eigen::Vector3d((u - s.cx) / s.fx, (v - s.cy) / s.fy, 1.0));
}

// The exact depth of every pixel that returns one (NaN otherwise), and for a painted world the
// triangle it sees and how squarely.
struct ExactDepth {
  std::vector<double> depth;
  std::vector<std::int32_t> seen_triangle;
  std::vector<double> facing;
};

ExactDepth exact_depth(const detail::MeshTree& mesh_tree, const Eigen::Isometry3d& T_world_sensor,
                       const DepthSensorSettings& s, bool painted) {
  const detail::AabbTree& tree = mesh_tree.tree;
  const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
  const Eigen::Vector3d origin = T_world_sensor.translation();
  const Eigen::Vector3d projector = T_world_sensor * Eigen::Vector3d(s.baseline, 0.0, 0.0);
  const double cos_max_incidence = std::cos(s.max_incidence);
  ExactDepth out{std::vector<double>(pixels, std::nan("")),
                 std::vector<std::int32_t>(painted ? pixels : 0, -1),
                 std::vector<double>(painted ? pixels : 0, 0.0)};
  tbb::parallel_for(0, s.height, [&](int v) {
    for (int u = 0; u < s.width; ++u) {
      const Eigen::Vector3d direction = pixel_ray(T_world_sensor, s, u, v);
      const auto hit = first_hit(tree, origin, origin + direction);
      if (!hit) continue;
      const Eigen::Vector3d& p = hit->first;
      const double z = (p - origin).dot(direction) / direction.squaredNorm();
      if (z < s.min_range || z > s.max_range) continue;
      const detail::Triangle& tri = *hit->second;
      const Kernel::Vector_3 n = CGAL::cross_product(tri[1] - tri[0], tri[2] - tri[0]);
      const Eigen::Vector3d normal = Eigen::Vector3d(n.x(), n.y(), n.z()).normalized();
      if (std::abs(normal.dot(direction.normalized())) < cos_max_incidence) continue;
      if (s.shadows) {
        // The projector's ray to p stops at a nearer surface: p is in its shadow (1 mm of slack
        // for the intersection's rounding on p's own triangle).
        const auto lit = first_hit(tree, projector, p);
        if (lit && (lit->first - projector).norm() < (p - projector).norm() - 1e-3) continue;
      }
      const std::size_t i = static_cast<std::size_t>(v) * s.width + u;
      out.depth[i] = z;
      if (painted) {
        out.seen_triangle[i] = static_cast<std::int32_t>(&tri - mesh_tree.triangles.data());
        out.facing[i] = std::abs(normal.dot(direction.normalized()));
      }
    }
  });
  return out;
}

}  // namespace

PointCloud render_depth(const TriangleMesh& world, const Eigen::Isometry3d& T_world_sensor,
                        const DepthSensorSettings& s) {
  check_sensor_settings(s);
  const detail::MeshTree mesh_tree(world);

  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(s.width);
  cloud.height = static_cast<std::uint32_t>(s.height);
  const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
  cloud.points.assign(pixels, Eigen::Vector3f::Constant(std::nanf("")));
  cloud.T_cloud_sensor = T_world_sensor;
  if (!world.colours.empty()) {
    if (world.colours.size() != world.triangles.size()) {
      throw Error("render_depth: a painted mesh needs one colour per triangle");
    }
    cloud.colors.assign(pixels, Color{0, 0, 0});
  }
  if (mesh_tree.triangles.empty()) return cloud;

  const bool painted = world.colours.size() == world.triangles.size() && !world.colours.empty();
  const ExactDepth exact = exact_depth(mesh_tree, T_world_sensor, s, painted);
  std::vector<double> measured = exact.depth;
  if (s.noise && s.flying_pixel_rate > 0.0) add_flying_pixels(exact.depth, s, measured);
  const std::vector<double> noise = s.noise ? sensor_noise_field(s) : std::vector<double>();

  const Eigen::Vector3d origin = T_world_sensor.translation();
  tbb::parallel_for(0, s.height, [&](int v) {
    for (int u = 0; u < s.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * s.width + u;
      if (std::isnan(measured[i])) continue;
      const double z = s.noise ? sensor_depth(measured[i], noise[i], s) : measured[i];
      cloud.points[i] = (origin + pixel_ray(T_world_sensor, s, u, v) * z).cast<float>();
      if (painted && exact.seen_triangle[i] >= 0) {
        cloud.colors[i] =
            shaded_colour(world.colours[static_cast<std::size_t>(exact.seen_triangle[i])],
                          exact.facing[i], pixel_stream(s.seed, i, kColourStream), s);
      }
    }
  });
  return cloud;
}

}  // namespace lmk
