// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/tsdf_volume.h"

#include <openvdb/tools/Morphology.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/geometry/range_image.h"
#include "lmk/occupancy/detail/vdb_support.h"

namespace lmk {

namespace vdb = openvdb;

struct TsdfVolume::Grid {
  double voxel = 0.0;
  PinholeIntrinsics first_intrinsics;  ///< the first frame's, fitted to its pixels
  vdb::FloatGrid::Ptr distance;        ///< weighted mean truncated distance, band widths
  vdb::FloatGrid::Ptr weight;          ///< summed weights; active voxels are the allocated ones
};

namespace {

// Where `p` (optical frame, in front of the camera) projects in the image of `k`: u right, v down,
// pixel centres at whole numbers.
template <typename Scalar>
Eigen::Matrix<Scalar, 2, 1> pixel_coordinates(const PinholeIntrinsics& k,
                                              const Eigen::Matrix<Scalar, 3, 1>& p) {
  return {static_cast<Scalar>(k.fx) * p.x() / p.z() + static_cast<Scalar>(k.cx),
          static_cast<Scalar>(k.fy) * p.y() / p.z() + static_cast<Scalar>(k.cy)};
}

// A frame ready to be looked into: its depth image, its intrinsics and the way from the common
// frame into its sensor's optical frame.
struct PreparedFrame {
  RangeImage image;
  Eigen::Isometry3f T_sensor_common;

  struct Look {
    float depth;     ///< the point's own depth, m
    float measured;  ///< the depth measured along its ray, m; NaN for none
  };
  // What the frame measured along the ray through `x` (common frame): its depth interpolated
  // bilinearly between the four pixels about the ray when all four measured one surface (within
  // `continuity` of each other), the nearest pixel's otherwise. Pixels are a few millimetres
  // apart at range: a slanted surface's depth changes that much from one to the next, and the
  // nearest pixel alone would move the zero crossing by it.
  Look look(const Eigen::Vector3f& x, float continuity) const {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Eigen::Vector3f p = T_sensor_common * x;
    if (!(p.z() > 0.0f)) return {p.z(), nan};
    const PinholeIntrinsics& k = image.intrinsics();
    const Eigen::Vector2f pixel = pixel_coordinates(k, p);
    const float u = pixel.x(), v = pixel.y();
    if (!(u > -0.5f && v > -0.5f && u < k.width - 0.5f && v < k.height - 0.5f)) return {p.z(), nan};
    const std::vector<float>& depth = image.depths();
    const auto at = [&](int col, int row) {
      return depth[static_cast<std::size_t>(row) * k.width + col];
    };
    const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
    if (u0 >= 0 && v0 >= 0 && u0 + 1 < k.width && v0 + 1 < k.height) {
      const float a = at(u0, v0), b = at(u0 + 1, v0), c = at(u0, v0 + 1), d = at(u0 + 1, v0 + 1);
      const float lo = std::min({a, b, c, d}), hi = std::max({a, b, c, d});
      if (std::isfinite(lo) && std::isfinite(hi) && hi - lo <= continuity) {
        const float fu = u - static_cast<float>(u0), fv = v - static_cast<float>(v0);
        return {p.z(), (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d)};
      }
    }
    return {p.z(), at(static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v)))};
  }
};

// Each frame's image (fitting its intrinsics reads every pixel: the frames in parallel).
std::vector<PreparedFrame> prepare(const std::vector<DepthFrame>& frames) {
  if (frames.empty()) throw Error("fuse: no frame");
  if (frames.size() > kMaxFusedFrames) {
    throw Error("fuse: " + std::to_string(frames.size()) + " frames: at most " +
                std::to_string(kMaxFusedFrames));
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string what = "fuse: frame " + std::to_string(i + 1);
    const PointCloud* cloud = frames[i].cloud;
    if (cloud == nullptr) throw Error(what + ": no cloud");
    if (!cloud->is_organized()) {
      throw Error(what + ": an unorganised cloud (frames are fused through their depth images)");
    }
    if (!frames[i].T_common_cloud.matrix().allFinite()) throw Error(what + ": pose not finite");
  }
  std::vector<std::optional<RangeImage>> images(frames.size());
  tbb::parallel_for(std::size_t{0}, frames.size(),
                    [&](std::size_t i) { images[i] = RangeImage::from_cloud(*frames[i].cloud); });
  std::vector<PreparedFrame> out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (!images[i]) {
      throw Error("fuse: frame " + std::to_string(i + 1) +
                  ": its pixels are no pinhole view from its sensor pose (a wrong VIEWPOINT?)");
    }
    const Eigen::Isometry3d T_common_sensor =
        frames[i].T_common_cloud * frames[i].cloud->T_cloud_sensor;
    out.push_back({std::move(*images[i]), T_common_sensor.inverse().cast<float>()});
  }
  return out;
}

// The band and the weight of a depth measured at `depth`: the band is truncation_sigmas of its
// noise (at least four voxels), the weight 1 / sigma^2 relative to a measurement at 1 m.
struct Measurement {
  float band;
  float weight;
};
Measurement measurement_at(double depth, const FusionSettings& s) {
  const double sigma = std::max(s.noise.measurement_sigma(depth), 0.25 * s.voxel_size);
  const double at_one_metre = std::max(s.noise.measurement_sigma(1.0), 0.25 * s.voxel_size);
  // At least four voxels: a surface seen obliquely changes its projective distance by several
  // voxels' worth from one voxel to the next, and a crossing needs both sides inside the band.
  return {static_cast<float>(std::max(s.truncation_sigmas * sigma, 4.0 * s.voxel_size)),
          static_cast<float>((at_one_metre * at_one_metre) / (sigma * sigma))};
}

// measurement_at() by the millimetre, out to 10 m: looked up twice per voxel and frame.
class MeasurementTable {
 public:
  explicit MeasurementTable(const FusionSettings& s) {
    for (int mm = 0; mm <= kSteps; ++mm) table_.push_back(measurement_at(1e-3 * mm, s));
  }
  const Measurement& at(float depth) const {
    const int mm = static_cast<int>(depth * 1000.0f + 0.5f);
    return table_[static_cast<std::size_t>(std::clamp(mm, 0, kSteps))];
  }

 private:
  static constexpr int kSteps = 10000;  // 10 m: beyond any depth camera's range
  std::vector<Measurement> table_;
};

// The voxels every frame measured a surface in, dilated by kShell voxels: the voxels the volume
// keeps. Free space far from every surface is not stored.
constexpr int kShell = 2;
vdb::FloatGrid::Ptr allocate(const std::vector<DepthFrame>& frames, const FusionSettings& s) {
  auto weight = vdb::FloatGrid::create(0.0f);
  weight->setTransform(vdb::math::Transform::createLinearTransform(s.voxel_size));
  auto accessor = weight->getAccessor();
  const double inverse_voxel = 1.0 / s.voxel_size;
  for (const DepthFrame& f : frames) {
    const Eigen::Isometry3f T = f.T_common_cloud.cast<float>();
    for (const Eigen::Vector3f& p : f.cloud->points) {
      if (!is_finite(p)) continue;
      accessor.setValueOn(detail::nearest_voxel((T * p).cast<double>(), inverse_voxel), 0.0f);
    }
  }
  // Two voxels about each measured one hold the crossing and the gradient beside it, and where
  // another frame saw past the surface, its carving; the band sets the values, not the extent.
  vdb::tools::dilateActiveValues(weight->tree(), kShell, vdb::tools::NN_FACE_EDGE_VERTEX,
                                 vdb::tools::IGNORE_TILES);
  return weight;
}

// Curless and Levoy's update of every kept voxel by every frame that saw it: the projective
// distance to the surface its pixel measured, truncated to the band, averaged by weight. A frame
// that saw clearly past the voxel carves it (+1); one whose surface lies clearly in front of it
// saw nothing of it.
vdb::FloatGrid::Ptr integrate(vdb::FloatGrid& weights, const std::vector<PreparedFrame>& frames,
                              const FusionSettings& s) {
  auto distances = vdb::FloatGrid::create(1.0f);
  distances->setTransform(weights.transform().copy());
  distances->tree().topologyUnion(weights.tree());
  vdb::tree::LeafManager<vdb::FloatTree> leaves(weights.tree());
  vdb::FloatTree& distance_tree = distances->tree();
  const double voxel = s.voxel_size;
  // Four pixels further apart in depth than two voxels do not hold one surface between them.
  const float continuity = static_cast<float>(2.0 * voxel);
  const MeasurementTable measurements(s);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t n = range.begin(); n < range.end(); ++n) {
                        vdb::FloatTree::LeafNodeType& w = leaves.leaf(n);
                        vdb::FloatTree::LeafNodeType* d = distance_tree.probeLeaf(w.origin());
                        for (auto v = w.beginValueOn(); v; ++v) {
                          const vdb::Coord c = v.getCoord();
                          const Eigen::Vector3f x(static_cast<float>(c.x() * voxel),
                                                  static_cast<float>(c.y() * voxel),
                                                  static_cast<float>(c.z() * voxel));
                          float sum = 0.0f, weight = 0.0f;
                          for (const PreparedFrame& f : frames) {
                            const PreparedFrame::Look look = f.look(x, continuity);
                            if (std::isnan(look.measured)) continue;
                            const float gap = look.measured - look.depth;
                            const float band = measurements.at(look.measured).band;
                            if (gap < -band) continue;  // behind the surface: unseen
                            // Weighed at the voxel's own depth: a frame that saw a far surface
                            // through a near voxel is as sure of it as one that measured there.
                            const float w = measurements.at(look.depth).weight;
                            sum += w * std::min(1.0f, gap / band);
                            weight += w;
                          }
                          const std::size_t k = v.pos();
                          if (weight > 0.0f) {
                            w.setValueOnly(k, weight);
                            d->setValueOnly(k, sum / weight);
                          } else {
                            w.setValueOff(k);
                            d->setValueOff(k);
                          }
                        }
                      }
                    });
  return distances;
}

// The crossings (common frame, with normals) seen by the camera `k` at T_common_sensor, each
// splatted over the pixels its voxel covers, the nearest kept per pixel (TsdfVolume::render()).
PointCloud render_crossings(const PointCloud& crossings, double voxel_size,
                            const PinholeIntrinsics& k, const Eigen::Isometry3d& T_common_sensor) {
  k.validate("fuse: render");
  const std::size_t pixels = static_cast<std::size_t>(k.width) * static_cast<std::size_t>(k.height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  PointCloud out;
  out.points.assign(pixels, Eigen::Vector3f::Constant(nan));
  out.normals.assign(pixels, Eigen::Vector3f::Constant(nan));
  out.width = static_cast<std::uint32_t>(k.width);
  out.height = static_cast<std::uint32_t>(k.height);
  out.T_cloud_sensor = T_common_sensor;
  std::vector<float> depth(pixels, std::numeric_limits<float>::infinity());
  const Eigen::Isometry3f T_sensor_common = T_common_sensor.inverse().cast<float>();
  const Eigen::Isometry3f T_common_sensor_f = T_common_sensor.cast<float>();
  const float voxel = static_cast<float>(voxel_size);
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    const Eigen::Vector3f p = T_sensor_common * crossings.points[i];
    if (p.z() <= 0.0f) continue;
    const Eigen::Vector3f n = T_sensor_common.linear() * crossings.normals[i];
    const Eigen::Vector2f pixel = pixel_coordinates(k, p);
    const float u = pixel.x(), v = pixel.y();
    // The pixels the crossing's voxel covers: a splat half a voxel wide about it.
    const float radius = 0.5f * voxel * static_cast<float>(k.fx) / p.z();
    const int u0 = std::max(0, static_cast<int>(std::floor(u - radius + 0.5f)));
    const int u1 = std::min(k.width - 1, static_cast<int>(std::floor(u + radius + 0.5f)));
    const int v0 = std::max(0, static_cast<int>(std::floor(v - radius + 0.5f)));
    const int v1 = std::min(k.height - 1, static_cast<int>(std::floor(v + radius + 0.5f)));
    for (int row = v0; row <= v1; ++row) {
      for (int col = u0; col <= u1; ++col) {
        const Eigen::Vector3f ray(
            (static_cast<float>(col) - static_cast<float>(k.cx)) / static_cast<float>(k.fx),
            (static_cast<float>(row) - static_cast<float>(k.cy)) / static_cast<float>(k.fy), 1.0f);
        // Where the pixel's ray meets the crossing's tangent plane; its own depth when the plane
        // is seen edge-on or the meeting strays beyond its voxel.
        Eigen::Vector3f q = ray * p.z();
        const float facing = n.dot(ray);
        if (std::isfinite(facing) && std::abs(facing) > 0.2f * ray.norm()) {
          const Eigen::Vector3f on_plane = ray * (n.dot(p) / facing);
          if ((on_plane - p).norm() <= voxel) q = on_plane;
        }
        const std::size_t index = static_cast<std::size_t>(row) * k.width + col;
        if (!(q.z() > 0.0f) || q.z() >= depth[index]) continue;
        depth[index] = q.z();
        out.points[index] = T_common_sensor_f * q;
        out.normals[index] = T_common_sensor_f.linear() * n;
      }
    }
  }
  return out;
}

}  // namespace

void FusionSettings::validate() const {
  if (!(voxel_size > 0.0 && voxel_size <= 0.1)) {
    throw Error("fuse: voxel size " + std::to_string(voxel_size) + " m: must be in (0, 0.1]");
  }
  if (!(truncation_sigmas >= 1.0 && truncation_sigmas <= 20.0)) {
    throw Error("fuse: truncation " + std::to_string(truncation_sigmas) +
                " sigmas: must be in [1, 20]");
  }
  if (!(max_canvas_growth >= 1.0 && max_canvas_growth <= 4.0)) {
    throw Error("fuse: canvas growth " + std::to_string(max_canvas_growth) + ": must be in [1, 4]");
  }
}

TsdfVolume::TsdfVolume(std::unique_ptr<Grid> grid) : grid_(std::move(grid)) {}
TsdfVolume::~TsdfVolume() = default;
TsdfVolume::TsdfVolume(TsdfVolume&&) noexcept = default;
TsdfVolume& TsdfVolume::operator=(TsdfVolume&&) noexcept = default;

TsdfVolume TsdfVolume::fuse(const std::vector<DepthFrame>& frames, const FusionSettings& settings) {
  settings.validate();
  detail::initialize_openvdb();
  const std::vector<PreparedFrame> prepared = prepare(frames);
  auto grid = std::make_unique<Grid>();
  grid->voxel = settings.voxel_size;
  grid->first_intrinsics = prepared.front().image.intrinsics();
  grid->weight = allocate(frames, settings);
  grid->distance = integrate(*grid->weight, prepared, settings);
  return TsdfVolume(std::move(grid));
}

std::size_t TsdfVolume::observed_voxels() const {
  return static_cast<std::size_t>(grid_->weight->activeVoxelCount());
}

double TsdfVolume::voxel_size() const { return grid_->voxel; }

const PinholeIntrinsics& TsdfVolume::first_intrinsics() const { return grid_->first_intrinsics; }

std::optional<TsdfVolume::Sample> TsdfVolume::sample(const Eigen::Vector3d& p) const {
  const vdb::Coord c = detail::nearest_voxel(p, 1.0 / grid_->voxel);
  const auto weight = grid_->weight->getConstAccessor();
  if (!weight.isValueOn(c)) return std::nullopt;
  return Sample{grid_->distance->getConstAccessor().getValue(c), weight.getValue(c)};
}

PointCloud TsdfVolume::surface() const {
  const double voxel = grid_->voxel;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  vdb::tree::LeafManager<const vdb::FloatTree> leaves(grid_->weight->tree());
  // Per leaf, in the leaves' order: the same crossings in the same order whatever the threads.
  std::vector<PointCloud> per_leaf(leaves.leafCount());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      const auto distance = grid_->distance->getConstAccessor();
                      const auto weight = grid_->weight->getConstAccessor();
                      // The distance at `c` when observed.
                      const auto at = [&](const vdb::Coord& c, float& value) {
                        if (!weight.isValueOn(c)) return false;
                        value = distance.getValue(c);
                        return true;
                      };
                      // The unit gradient at `c` by central differences where both neighbours were
                      // observed, one-sided else: the normal, pointing to free space.
                      const auto normal_at = [&](const vdb::Coord& c, float here) {
                        Eigen::Vector3f gradient;
                        for (int axis = 0; axis < 3; ++axis) {
                          vdb::Coord step(0, 0, 0);
                          step[axis] = 1;
                          float ahead = 0.0f, behind = 0.0f;
                          const bool has_ahead = at(c + step, ahead),
                                     has_behind = at(c - step, behind);
                          gradient[axis] = has_ahead && has_behind ? 0.5f * (ahead - behind)
                                           : has_ahead             ? ahead - here
                                           : has_behind            ? here - behind
                                                                   : nan;
                        }
                        const float length = gradient.norm();
                        return length > 1e-6f ? Eigen::Vector3f(gradient / length)
                                              : Eigen::Vector3f::Constant(nan);
                      };
                      for (std::size_t n = range.begin(); n < range.end(); ++n) {
                        PointCloud& out = per_leaf[n];
                        const vdb::FloatTree::LeafNodeType& leaf = leaves.leaf(n);
                        for (auto v = leaf.cbeginValueOn(); v; ++v) {
                          const vdb::Coord c = v.getCoord();
                          const float here = distance.getValue(c);
                          if (!(std::abs(here) < 1.0f)) continue;  // truncated: says only "beyond"
                          for (int axis = 0; axis < 3; ++axis) {
                            vdb::Coord step(0, 0, 0);
                            step[axis] = 1;
                            float next = 0.0f;
                            if (!at(c + step, next) || (here > 0.0f) == (next > 0.0f) ||
                                !(std::abs(next) < 1.0f)) {
                              continue;  // no crossing, or one beside a truncated value
                            }
                            const float t = here / (here - next);
                            Eigen::Vector3f p(static_cast<float>(c.x() * voxel),
                                              static_cast<float>(c.y() * voxel),
                                              static_cast<float>(c.z() * voxel));
                            p[axis] += t * static_cast<float>(voxel);
                            out.points.push_back(p);
                            out.normals.push_back(normal_at(c, here));
                          }
                        }
                      }
                    });
  PointCloud out;
  for (const PointCloud& leaf : per_leaf) {
    out.points.insert(out.points.end(), leaf.points.begin(), leaf.points.end());
    out.normals.insert(out.normals.end(), leaf.normals.begin(), leaf.normals.end());
  }
  out.width = static_cast<std::uint32_t>(out.points.size());
  out.height = 1;
  return out;
}

PointCloud TsdfVolume::render(const PinholeIntrinsics& k,
                              const Eigen::Isometry3d& T_common_sensor) const {
  return render_crossings(surface(), grid_->voxel, k, T_common_sensor);
}

PointCloud fuse_frames(const std::vector<DepthFrame>& frames, const FusionSettings& settings) {
  settings.validate();
  if (frames.size() == 1) {
    if (frames.front().cloud == nullptr) throw Error("fuse: frame 1: no cloud");
    return frames.front().cloud->transformed(frames.front().T_common_cloud);
  }
  const TsdfVolume volume = TsdfVolume::fuse(frames, settings);
  // The first frame's view, grown to hold what the other frames saw beyond its edges.
  const DepthFrame& first = frames.front();
  const Eigen::Isometry3d T_common_sensor = first.T_common_cloud * first.cloud->T_cloud_sensor;
  PinholeIntrinsics k = volume.first_intrinsics();
  const PointCloud crossings = volume.surface();
  const Eigen::Isometry3f T_sensor_common = T_common_sensor.inverse().cast<float>();
  double u_min = 0.0, u_max = k.width - 1.0, v_min = 0.0, v_max = k.height - 1.0;
  for (const Eigen::Vector3f& point : crossings.points) {
    const Eigen::Vector3f p = T_sensor_common * point;
    if (p.z() <= 0.0f) continue;
    const Eigen::Vector2d pixel = pixel_coordinates(k, Eigen::Vector3d(p.cast<double>()));
    const double u = pixel.x(), v = pixel.y();
    u_min = std::min(u_min, u), u_max = std::max(u_max, u);
    v_min = std::min(v_min, v), v_max = std::max(v_max, v);
  }
  const double grow_u = 0.5 * (settings.max_canvas_growth - 1.0) * k.width;
  const double grow_v = 0.5 * (settings.max_canvas_growth - 1.0) * k.height;
  // A pixel holds what projects within half a pixel of its centre.
  const auto grow = [](double beyond, double most) {
    return static_cast<int>(std::ceil(std::clamp(beyond - 0.5, 0.0, most)));
  };
  const int left = grow(-u_min, grow_u), right = grow(u_max - (k.width - 1.0), grow_u);
  const int top = grow(-v_min, grow_v), bottom = grow(v_max - (k.height - 1.0), grow_v);
  k.cx += left, k.cy += top;
  k.width += left + right, k.height += top + bottom;
  return render_crossings(crossings, volume.voxel_size(), k, T_common_sensor);
}

}  // namespace lmk
