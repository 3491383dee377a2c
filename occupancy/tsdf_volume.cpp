// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/tsdf_volume.h"

#include <openvdb/tools/Morphology.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <unordered_set>

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
  PreparedFrame(RangeImage range_image, const Eigen::Isometry3f& T)
      : image(std::move(range_image)),
        T_sensor_common(T),
        fx(static_cast<float>(image.intrinsics().fx)),
        fy(static_cast<float>(image.intrinsics().fy)),
        cx(static_cast<float>(image.intrinsics().cx)),
        cy(static_cast<float>(image.intrinsics().cy)),
        width(image.intrinsics().width),
        height(image.intrinsics().height) {}

  RangeImage image;
  Eigen::Isometry3f T_sensor_common;
  float fx, fy, cx, cy;  ///< the intrinsics in single precision, read per voxel
  int width, height;

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
    const float inverse_z = 1.0f / p.z();
    const float u = fx * p.x() * inverse_z + cx, v = fy * p.y() * inverse_z + cy;
    if (!(u > -0.5f && v > -0.5f && u < width - 0.5f && v < height - 0.5f)) return {p.z(), nan};
    const float* depth = image.depths().data();
    const auto at = [&](int col, int row) {
      return depth[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(col)];
    };
    // u, v > -0.5: truncation after adding 1 is floor, after adding 0.5 rounding (std::floor and
    // std::lround are library calls on baseline x86-64, here twice per voxel and frame).
    const int u0 = static_cast<int>(u + 1.0f) - 1, v0 = static_cast<int>(v + 1.0f) - 1;
    if (u0 >= 0 && v0 >= 0 && u0 + 1 < width && v0 + 1 < height) {
      const float a = at(u0, v0), b = at(u0 + 1, v0), c = at(u0, v0 + 1), d = at(u0 + 1, v0 + 1);
      // All four measured (a NaN compares false, so min and max alone could pass one by).
      // A hole among the four: the ray passes the edge of what the frame measured, and a surface
      // extended into the hole from the nearest pixel would fatten every silhouette.
      if (!std::isfinite(a + b + c + d)) return {p.z(), nan};
      if (std::max({a, b, c, d}) - std::min({a, b, c, d}) <= continuity) {
        const float fu = u - static_cast<float>(u0), fv = v - static_cast<float>(v0);
        return {p.z(), (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d)};
      }
    }
    return {p.z(), at(static_cast<int>(u + 0.5f), static_cast<int>(v + 0.5f))};
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
    out.emplace_back(std::move(*images[i]), T_common_sensor.inverse().cast<float>());
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
// A leaf node's bytes in the volume: the distance's and the weight's 8^3 floats with their masks,
// and the marked topology's mask leaf per thread.
constexpr std::size_t kBytesPerLeaf = 2 * (512 * sizeof(float) + 2 * 64 + 32) + 2 * 96;

vdb::FloatGrid::Ptr allocate(const std::vector<DepthFrame>& frames, const FusionSettings& s) {
  // Blocks of rows of every frame, marked in parallel into a topology per thread, then merged:
  // the union of sets, whatever the threads.
  constexpr std::uint32_t kRows = 32;
  std::vector<std::pair<std::size_t, std::uint32_t>> blocks;  // frame, first row
  for (std::size_t f = 0; f < frames.size(); ++f) {
    for (std::uint32_t row = 0; row < frames[f].cloud->height; row += kRows) {
      blocks.emplace_back(f, row);
    }
  }
  const double inverse_voxel = 1.0 / s.voxel_size;
  tbb::enumerable_thread_specific<vdb::MaskTree> marked;
  tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t b) {
    const DepthFrame& f = frames[blocks[b].first];
    const Eigen::Isometry3f T = f.T_common_cloud.cast<float>();
    vdb::tree::ValueAccessor<vdb::MaskTree> accessor(marked.local());
    const std::size_t width = f.cloud->width;
    const std::size_t begin = blocks[b].second * width;
    const std::size_t end = std::min<std::size_t>(begin + kRows * width, f.cloud->points.size());
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3f& p = f.cloud->points[i];
      if (!is_finite(p)) continue;
      accessor.setValueOn(detail::nearest_voxel((T * p).cast<double>(), inverse_voxel));
    }
  });
  auto weight = vdb::FloatGrid::create(0.0f);
  weight->setTransform(vdb::math::Transform::createLinearTransform(s.voxel_size));
  for (const vdb::MaskTree& tree : marked) weight->tree().topologyUnion(tree);
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

// One crossing as the camera sees it: in the sensor frame, and the pixels its voxel covers.
struct Splat {
  Eigen::Vector3f p, n;  ///< sensor frame
  int u0 = 0, u1 = -1, v0 = 0, v1 = -1;
};

// Where the ray of pixel (col, row) meets the splat's tangent plane, sensor frame; the splat's own
// depth along the ray when the plane is seen edge-on or the meeting strays beyond its voxel.
Eigen::Vector3f meeting(const Splat& s, const PinholeIntrinsics& k, int col, int row, float voxel) {
  const Eigen::Vector3f ray(
      (static_cast<float>(col) - static_cast<float>(k.cx)) / static_cast<float>(k.fx),
      (static_cast<float>(row) - static_cast<float>(k.cy)) / static_cast<float>(k.fy), 1.0f);
  const float facing = s.n.dot(ray);
  if (std::isfinite(facing) && facing * facing > 0.04f * ray.squaredNorm()) {
    const Eigen::Vector3f on_plane = ray * (s.n.dot(s.p) / facing);
    if ((on_plane - s.p).squaredNorm() <= voxel * voxel) return on_plane;
  }
  return ray * s.p.z();
}

// The crossings (common frame, with normals) seen by the camera `k` at T_common_sensor, each
// splatted over the pixels its voxel covers, the nearest kept per pixel (TsdfVolume::render()).
// Blocks of rows in parallel, each pixel's nearest meeting decided by (depth, crossing): the same
// frame whatever the threads.
// Each crossing as a splat in the sensor frame: its point, normal and the pixel window its voxel
// covers (empty behind the camera).
std::vector<Splat> splats_of(const PointCloud& crossings, float voxel, const PinholeIntrinsics& k,
                             const Eigen::Isometry3f& T_sensor_common) {
  std::vector<Splat> splats(crossings.size());
  tbb::parallel_for(std::size_t{0}, crossings.size(), [&](std::size_t i) {
    Splat& s = splats[i];
    s.p = T_sensor_common * crossings.points[i];
    if (!(s.p.z() > 0.0f)) return;  // behind the camera: an empty window
    s.n = T_sensor_common.linear() * crossings.normals[i];
    const Eigen::Vector2f pixel = pixel_coordinates(k, s.p);
    // The pixels the crossing's voxel covers: a splat half a voxel wide about it.
    const float radius = 0.5f * voxel * static_cast<float>(k.fx) / s.p.z();
    // floor(x + 0.5) within the image (truncation is floor from 0 on).
    const auto first = [](float x, int size) {
      return static_cast<int>(std::clamp(x + 0.5f, 0.0f, static_cast<float>(size)));
    };
    const auto last = [](float x, int size) {
      return x + 0.5f < 0.0f ? -1 : static_cast<int>(std::min(x + 0.5f, size - 1.0f));
    };
    s.u0 = first(pixel.x() - radius, k.width), s.u1 = last(pixel.x() + radius, k.width);
    s.v0 = first(pixel.y() - radius, k.height), s.v1 = last(pixel.y() + radius, k.height);
  });
  return splats;
}

// The splats by their first row (in crossing order within a row: by_row[row_start[r]] onwards),
// and the most rows one spans.
struct SplatRows {
  std::vector<std::size_t> row_start;
  std::vector<std::uint32_t> by_row;
  int span = 0;
};

SplatRows rows_of(const std::vector<Splat>& splats, int height) {
  SplatRows rows;
  rows.row_start.assign(static_cast<std::size_t>(height) + 1, 0);
  for (const Splat& s : splats) {
    if (s.v0 > s.v1 || s.u0 > s.u1) continue;
    ++rows.row_start[static_cast<std::size_t>(s.v0) + 1];
    rows.span = std::max(rows.span, s.v1 - s.v0);
  }
  for (std::size_t r = 0; r < static_cast<std::size_t>(height); ++r) {
    rows.row_start[r + 1] += rows.row_start[r];
  }
  rows.by_row.resize(rows.row_start.back());
  std::vector<std::size_t> fill(rows.row_start.begin(), rows.row_start.end() - 1);
  for (std::size_t i = 0; i < splats.size(); ++i) {
    const Splat& s = splats[i];
    if (s.v0 > s.v1 || s.u0 > s.u1) continue;
    rows.by_row[fill[static_cast<std::size_t>(s.v0)]++] = static_cast<std::uint32_t>(i);
  }
  return rows;
}

constexpr std::uint64_t kNoMeeting = std::numeric_limits<std::uint64_t>::max();

// Per pixel the nearest meeting as (depth's bits, crossing): a positive float's bits order as
// the float does, and a tie goes to the first crossing, as a serial pass would keep it.
std::vector<std::uint64_t> nearest_meetings(const std::vector<Splat>& splats, const SplatRows& rows,
                                            const PinholeIntrinsics& k, float voxel) {
  const std::size_t pixels = static_cast<std::size_t>(k.width) * static_cast<std::size_t>(k.height);
  std::vector<std::uint64_t> nearest(pixels, kNoMeeting);
  constexpr int kBlockRows = 16;
  tbb::parallel_for(0, (k.height + kBlockRows - 1) / kBlockRows, [&](int block) {
    const int top = block * kBlockRows, bottom = std::min(k.height, top + kBlockRows);
    for (int first_row = std::max(0, top - rows.span); first_row < bottom; ++first_row) {
      for (std::size_t j = rows.row_start[static_cast<std::size_t>(first_row)];
           j < rows.row_start[static_cast<std::size_t>(first_row) + 1]; ++j) {
        const Splat& s = splats[rows.by_row[j]];
        for (int row = std::max(s.v0, top); row <= std::min(s.v1, bottom - 1); ++row) {
          for (int col = s.u0; col <= s.u1; ++col) {
            const float depth = meeting(s, k, col, row, voxel).z();
            if (!(depth > 0.0f)) continue;
            std::uint32_t bits;
            std::memcpy(&bits, &depth, sizeof bits);
            const std::uint64_t key = (std::uint64_t{bits} << 32) | rows.by_row[j];
            std::uint64_t& here = nearest[static_cast<std::size_t>(row) * k.width + col];
            here = std::min(here, key);
          }
        }
      }
    }
  });
  return nearest;
}

PointCloud render_crossings(const PointCloud& crossings, double voxel_size,
                            const PinholeIntrinsics& k, const Eigen::Isometry3d& T_common_sensor) {
  k.validate("fuse: render");
  const std::size_t pixels = static_cast<std::size_t>(k.width) * static_cast<std::size_t>(k.height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float voxel = static_cast<float>(voxel_size);
  const std::vector<Splat> splats =
      splats_of(crossings, voxel, k, T_common_sensor.inverse().cast<float>());
  const std::vector<std::uint64_t> nearest =
      nearest_meetings(splats, rows_of(splats, k.height), k, voxel);
  PointCloud out;
  out.points.assign(pixels, Eigen::Vector3f::Constant(nan));
  out.normals.assign(pixels, Eigen::Vector3f::Constant(nan));
  out.width = static_cast<std::uint32_t>(k.width);
  out.height = static_cast<std::uint32_t>(k.height);
  out.T_cloud_sensor = T_common_sensor;
  const Eigen::Isometry3f T_common_sensor_f = T_common_sensor.cast<float>();
  tbb::parallel_for(std::size_t{0}, pixels, [&](std::size_t index) {
    if (nearest[index] == kNoMeeting) return;
    const Splat& s = splats[nearest[index] & 0xffffffffu];
    const int row = static_cast<int>(index / static_cast<std::size_t>(k.width));
    const int col = static_cast<int>(index % static_cast<std::size_t>(k.width));
    out.points[index] = T_common_sensor_f * meeting(s, k, col, row, voxel);
    out.normals[index] = T_common_sensor_f.linear() * s.n;
  });
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

std::size_t fusion_bytes(const std::vector<DepthFrame>& frames, const FusionSettings& settings,
                         std::size_t limit) {
  settings.validate();
  // The leaves the measured voxels and their shells (kShell voxels about each: at most two leaves
  // an axis) fall in, told apart by whole coordinates, so that no frame can fold leaves together.
  struct LeafHash {
    std::size_t operator()(const vdb::Coord& c) const { return c.hash<24>(); }
  };
  std::unordered_set<vdb::Coord, LeafHash> leaves;
  const double inverse_voxel = 1.0 / settings.voxel_size;
  const auto leaf = [](std::int64_t v) {
    return static_cast<vdb::Int32>(v >= 0 ? v / 8 : -((-v + 7) / 8));
  };
  std::optional<vdb::Coord> last;
  for (const DepthFrame& f : frames) {
    if (f.cloud == nullptr) continue;
    const Eigen::Isometry3f T = f.T_common_cloud.cast<float>();
    for (const Eigen::Vector3f& p : f.cloud->points) {
      if (!is_finite(p)) continue;
      const vdb::Coord c = detail::nearest_voxel((T * p).cast<double>(), inverse_voxel);
      const auto shell_leaf = [&c, &leaf](std::int64_t side) {
        return vdb::Coord(leaf(c.x() + side), leaf(c.y() + side), leaf(c.z() + side));
      };
      const vdb::Coord low = shell_leaf(-kShell), high = shell_leaf(kShell);
      // Neighbouring pixels mostly fall in the leaf of the one before: counted once.
      if (low == high && low == last) continue;
      if (low == high) last = low;
      for (vdb::Int32 x = low.x(); x <= high.x(); ++x) {
        for (vdb::Int32 y = low.y(); y <= high.y(); ++y) {
          for (vdb::Int32 z = low.z(); z <= high.z(); ++z) leaves.insert(vdb::Coord(x, y, z));
        }
      }
      if (leaves.size() * kBytesPerLeaf > limit) return leaves.size() * kBytesPerLeaf;
    }
  }
  return leaves.size() * kBytesPerLeaf;
}

TsdfVolume TsdfVolume::fuse(const std::vector<DepthFrame>& frames, const FusionSettings& settings) {
  settings.validate();
  detail::initialize_openvdb();
  const std::vector<PreparedFrame> prepared = prepare(frames);
  if (settings.max_bytes != std::numeric_limits<std::size_t>::max()) {
    const std::size_t bytes = fusion_bytes(frames, settings, settings.max_bytes);
    if (bytes > settings.max_bytes) {
      throw Error("fuse: the volume would take over " + std::to_string(bytes / 1000000) +
                  " MB, more than the " + std::to_string(settings.max_bytes / 1000000) +
                  " MB allowed; fuse fewer frames or crop them");
    }
  }
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
