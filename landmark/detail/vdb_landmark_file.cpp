// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/detail/vdb_landmark_file.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/landmark/detail/landmark_container.h"
#include "lmk/landmark/internal/capture_findings_json.h"
#include "lmk/occupancy/internal/grids.h"

namespace lmk::detail {

namespace fs = std::filesystem;
namespace vdb = openvdb;

namespace {

constexpr const char* kPointsGrid = "points";
constexpr const char* kPositionAttribute = "capture_position";
// Version 2: each point's index in the landmark. OpenVDB keeps points in its own voxel order, and
// the stored closest-point grid names points by index, so loading must restore the capture order.
constexpr const char* kIndexAttribute = "capture_index";
// Version 3, a landmark of several views only: each point's views, one bit per view.
constexpr const char* kViewsAttribute = "capture_views";
// Version 3, a landmark with colour only: each point's 8-bit RGB, packed as 0xRRGGBB.
constexpr const char* kColourAttribute = "capture_colour";
// The version a landmark's file is written in: a landmark of one view without colour keeps version
// 2, byte for byte as lmk wrote it before views and colour existed.
constexpr int kOneViewFileVersion = 2;

// Version 4, the capture check's findings (capture_findings.h) as JSON text.
constexpr const char* kFindingsMeta = "lmk_capture_findings";
// The version that introduced views and colour, written for a landmark without findings that has
// either; 4 added the findings.
constexpr int kViewsFileVersion = 3;
constexpr int kFindingsFileVersion = 4;

int legacy_version(const Landmark& landmark) {
  if (landmark.findings.present) return kFindingsFileVersion;
  return landmark.multi_view() || landmark.points.has_colors() ? kViewsFileVersion
                                                               : kOneViewFileVersion;
}

std::int32_t packed_colour(const Color& c) {
  return static_cast<std::int32_t>((std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b);
}

Color unpacked_colour(std::int32_t packed) {
  const auto bits = static_cast<std::uint32_t>(packed);
  return {static_cast<std::uint8_t>(bits >> 16), static_cast<std::uint8_t>(bits >> 8),
          static_cast<std::uint8_t>(bits)};
}

std::string view_origin_meta(std::size_t view) { return "lmk_view_origin_" + std::to_string(view); }

void append_trailer(const fs::path& file) {
  const std::string trailer = landmark_trailer(read_input_file(file.string(), kLandmarkInput));
  std::ofstream out(file, std::ios::binary | std::ios::app);
  out.write(trailer.data(), static_cast<std::streamsize>(trailer.size()));
  if (!out) throw Error(file.string() + ": write failed");
}

// OpenVDB allocates what a file's grid headers declare. Behind a valid checksum that is a file
// written wrong, not damaged on the way: lmk reports it as corrupt instead of running out of
// memory.
Error corrupt_sizes(const std::string& path) {
  return Error(path + ": corrupt landmark file: its grids declare sizes beyond memory");
}

template <typename MetaT>
auto require_meta(const vdb::GridBase& grid, const std::string& name, const std::string& path) {
  const auto meta = grid.getMetadata<MetaT>(name);
  if (!meta) throw Error(path + ": not an lmk landmark file: metadata '" + name + "' is missing");
  return meta->value();
}

vdb::points::PointDataGrid::Ptr make_points_grid(const Landmark& landmark) {
  std::vector<vdb::Vec3f> positions;
  positions.reserve(landmark.points.size());
  for (const auto& p : landmark.points.points) positions.emplace_back(p.x(), p.y(), p.z());
  const auto transform = vdb::math::Transform::createLinearTransform(landmark.settings.leaf_size);
  const vdb::points::PointAttributeVector<vdb::Vec3f> wrapper(positions);
  const auto index_grid =
      vdb::tools::createPointIndexGrid<vdb::tools::PointIndexGrid>(wrapper, *transform);
  auto grid = vdb::points::createPointDataGrid<vdb::points::NullCodec, vdb::points::PointDataGrid>(
      *index_grid, wrapper, *transform);
  vdb::points::appendAttribute<vdb::Vec3f>(grid->tree(), kPositionAttribute);
  vdb::points::populateAttribute(grid->tree(), index_grid->tree(), kPositionAttribute, wrapper);
  std::vector<std::int32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0);
  vdb::points::appendAttribute<std::int32_t>(grid->tree(), kIndexAttribute);
  vdb::points::populateAttribute(grid->tree(), index_grid->tree(), kIndexAttribute,
                                 vdb::points::PointAttributeVector<std::int32_t>(order));
  if (landmark.multi_view()) {
    const std::vector<std::int32_t> views(landmark.point_views.begin(), landmark.point_views.end());
    vdb::points::appendAttribute<std::int32_t>(grid->tree(), kViewsAttribute);
    vdb::points::populateAttribute(grid->tree(), index_grid->tree(), kViewsAttribute,
                                   vdb::points::PointAttributeVector<std::int32_t>(views));
  }
  if (landmark.points.has_colors()) {
    std::vector<std::int32_t> colours;
    for (const Color& c : landmark.points.colors) colours.push_back(packed_colour(c));
    vdb::points::appendAttribute<std::int32_t>(grid->tree(), kColourAttribute);
    vdb::points::populateAttribute(grid->tree(), index_grid->tree(), kColourAttribute,
                                   vdb::points::PointAttributeVector<std::int32_t>(colours));
  }
  grid->setName(kPointsGrid);

  const Eigen::Matrix4d pose = landmark.box.pose.matrix();
  vdb::Mat4d box_pose;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) box_pose(r, c) = pose(r, c);
  const auto vec = [](const Eigen::Vector3d& v) { return vdb::Vec3d(v.x(), v.y(), v.z()); };
  grid->insertMeta("lmk_format_version", vdb::Int32Metadata(legacy_version(landmark)));
  grid->insertMeta("lmk_name", vdb::StringMetadata(landmark.name));
  grid->insertMeta("lmk_box_pose", vdb::Mat4DMetadata(box_pose));
  grid->insertMeta("lmk_box_size", vdb::Vec3DMetadata(vec(landmark.box.size)));
  grid->insertMeta("lmk_sensor_origin", vdb::Vec3DMetadata(vec(landmark.sensor_origin)));
  grid->insertMeta("lmk_leaf_size", vdb::DoubleMetadata(landmark.settings.leaf_size));
  grid->insertMeta("lmk_min_points",
                   vdb::Int64Metadata(static_cast<std::int64_t>(landmark.settings.min_points)));
  grid->insertMeta("lmk_max_box_side", vdb::DoubleMetadata(landmark.settings.max_box_side));
  grid->insertMeta("lmk_up", vdb::Vec3DMetadata(vec(landmark.up)));
  grid->insertMeta("lmk_distance_band", vdb::DoubleMetadata(landmark.settings.distance_band));
  grid->insertMeta("lmk_empty_space_margin",
                   vdb::DoubleMetadata(landmark.settings.empty_space_margin));
  // Optional: files without it hold a landmark with a shape, as every earlier file does.
  if (landmark.settings.allow_flat) grid->insertMeta("lmk_allow_flat", vdb::BoolMetadata(true));
  if (landmark.findings.present) {
    grid->insertMeta(
        kFindingsMeta,
        vdb::StringMetadata(detail::capture_findings_to_json(landmark.findings).dump()));
  }
  if (landmark.multi_view()) {  // the first view's origin is lmk_sensor_origin
    grid->insertMeta("lmk_view_count",
                     vdb::Int32Metadata(static_cast<std::int32_t>(landmark.view_origins.size())));
    for (std::size_t v = 1; v < landmark.view_origins.size(); ++v) {
      grid->insertMeta(view_origin_meta(v), vdb::Vec3DMetadata(vec(landmark.view_origins[v])));
    }
  }
  return grid;
}

Eigen::Vector3d eigen_vector(const vdb::Vec3d& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

// The landmark's box, sensor origin, up axis and capture settings, from the grid's metadata;
// lmk::Error for a version this lmk cannot read or a value missing.
void read_landmark_meta(const vdb::points::PointDataGrid& grid, const std::string& path,
                        Landmark& landmark) {
  landmark.format_version = require_meta<vdb::Int32Metadata>(grid, "lmk_format_version", path);
  if (landmark.format_version < 1 || landmark.format_version > kFindingsFileVersion) {
    throw Error(path + ": landmark format version " + std::to_string(landmark.format_version) +
                " is not supported (this lmk reads versions 1 to " +
                std::to_string(kFindingsFileVersion) + ")");
  }
  landmark.name = require_meta<vdb::StringMetadata>(grid, "lmk_name", path);
  const vdb::Mat4d pose = require_meta<vdb::Mat4DMetadata>(grid, "lmk_box_pose", path);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) landmark.box.pose.matrix()(r, c) = pose(r, c);
  landmark.box.size = eigen_vector(require_meta<vdb::Vec3DMetadata>(grid, "lmk_box_size", path));
  landmark.sensor_origin =
      eigen_vector(require_meta<vdb::Vec3DMetadata>(grid, "lmk_sensor_origin", path));
  landmark.settings.leaf_size = require_meta<vdb::DoubleMetadata>(grid, "lmk_leaf_size", path);
  const std::int64_t min_points = require_meta<vdb::Int64Metadata>(grid, "lmk_min_points", path);
  if (min_points < 0) throw Error(path + ": negative lmk_min_points");
  landmark.settings.min_points = static_cast<std::size_t>(min_points);
  landmark.settings.max_box_side =
      require_meta<vdb::DoubleMetadata>(grid, "lmk_max_box_side", path);
  if (landmark.format_version >= 2) {
    landmark.up = eigen_vector(require_meta<vdb::Vec3DMetadata>(grid, "lmk_up", path));
    landmark.settings.distance_band =
        require_meta<vdb::DoubleMetadata>(grid, "lmk_distance_band", path);
    landmark.settings.empty_space_margin =
        require_meta<vdb::DoubleMetadata>(grid, "lmk_empty_space_margin", path);
  }  // version 1 had neither: the defaults apply, and up is the capture camera's -y
  if (const auto flat = grid.getMetadata<vdb::BoolMetadata>("lmk_allow_flat")) {
    landmark.settings.allow_flat = flat->value();
  }
}

// A landmark of several views: each view's sensor origin, the first's being lmk_sensor_origin.
void read_view_origins(const vdb::points::PointDataGrid& grid, const std::string& path,
                       Landmark& landmark) {
  const std::int32_t count = require_meta<vdb::Int32Metadata>(grid, "lmk_view_count", path);
  if (count < 2 || count > static_cast<std::int32_t>(kMaxLandmarkViews)) {
    throw Error(path + ": corrupt landmark file: " + std::to_string(count) +
                " views (a landmark of several views has 2 to " +
                std::to_string(kMaxLandmarkViews) + ")");
  }
  landmark.view_origins.push_back(landmark.sensor_origin);
  for (std::int32_t v = 1; v < count; ++v) {
    landmark.view_origins.push_back(eigen_vector(require_meta<vdb::Vec3DMetadata>(
        grid, view_origin_meta(static_cast<std::size_t>(v)), path)));
  }
}

// lmk::Error unless `leaf` has `attribute`, with point offsets that fit its array. The leaf's voxel
// values are running point offsets into its attribute arrays; OpenVDB reads both from the file
// without checking that they agree (a disagreement failed an assertion inside OpenVDB). They must
// rise and stay within the array.
template <typename Leaf>
void require_attribute(const Leaf& leaf, const char* attribute, const std::string& path) {
  if (!leaf->hasAttribute(attribute)) {
    throw Error(path + ": not an lmk landmark file: points lack '" + std::string(attribute) + "'");
  }
  const vdb::points::AttributeArray& array = leaf->constAttributeArray(attribute);
  bool offsets_fit = array.stride() == 1;
  for (vdb::Index v = 0, previous = 0; offsets_fit && v < leaf->SIZE; ++v) {
    const vdb::Index offset = leaf->getValue(v);
    offsets_fit = offset >= previous && offset <= array.dataSize();
    previous = offset;
  }
  if (!offsets_fit) {
    throw Error(path + ": corrupt landmark file: a leaf's '" + std::string(attribute) +
                "' array: its point offsets do not fit it");
  }
}

// The points' attributes as the grid's leaves hold them, in leaf order: the positions always, the
// capture order, views and colours when the file has them.
struct LeafOrderPoints {
  std::vector<Eigen::Vector3f> positions;
  std::vector<std::int32_t> order, views, colours;
};

LeafOrderPoints read_points(const vdb::points::PointDataGrid& grid, const std::string& path,
                            bool ordered, bool views, bool colours) {
  LeafOrderPoints out;
  const auto read_int_attribute = [&](const auto& leaf, const char* attribute,
                                      std::vector<std::int32_t>& values) {
    require_attribute(leaf, attribute, path);
    const vdb::points::AttributeHandle<std::int32_t> handle(leaf->constAttributeArray(attribute));
    for (auto index = leaf->beginIndexOn(); index; ++index) values.push_back(handle.get(*index));
  };
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
    require_attribute(leaf, kPositionAttribute, path);
    if (views) read_int_attribute(leaf, kViewsAttribute, out.views);
    if (colours) read_int_attribute(leaf, kColourAttribute, out.colours);
    const vdb::points::AttributeHandle<vdb::Vec3f> handle(
        leaf->constAttributeArray(kPositionAttribute));
    for (auto index = leaf->beginIndexOn(); index; ++index) {
      const vdb::Vec3f p = handle.get(*index);
      out.positions.emplace_back(p.x(), p.y(), p.z());
    }
    if (ordered) read_int_attribute(leaf, kIndexAttribute, out.order);
  }
  return out;
}

// The points put back into capture order (which the closest-point grid refers to), with their
// views and colours; lmk::Error unless the stored order is a permutation.
void restore_capture_order(const LeafOrderPoints& read, bool views, bool colours,
                           const std::string& path, Landmark& landmark) {
  const std::vector<std::int32_t>& order = read.order;
  std::vector<Eigen::Vector3f> points(order.size(), Eigen::Vector3f::Constant(NAN));
  if (views) landmark.point_views.assign(order.size(), 0);
  if (colours) landmark.points.colors.assign(order.size(), Color{});
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto i = static_cast<std::size_t>(order[k]);
    if (order[k] < 0 || i >= points.size() || !std::isnan(points[i].x())) {
      throw Error(path + ": corrupt landmark file: the point indices are not a permutation");
    }
    points[i] = read.positions[k];
    if (views) landmark.point_views[i] = static_cast<std::uint32_t>(read.views[k]);
    if (colours) landmark.points.colors[i] = unpacked_colour(read.colours[k]);
  }
  landmark.points.points = std::move(points);
}

Landmark landmark_from_grid(const vdb::points::PointDataGrid& grid, const std::string& path) {
  Landmark landmark;
  read_landmark_meta(grid, path, landmark);
  // Version 3 holds views, colour or both.
  const bool views = landmark.format_version >= 3 &&
                     grid.getMetadata<vdb::Int32Metadata>("lmk_view_count") != nullptr;
  const auto first_leaf = grid.tree().cbeginLeaf();
  const bool colours =
      landmark.format_version >= 3 && first_leaf && first_leaf->hasAttribute(kColourAttribute);
  if (views) read_view_origins(grid, path, landmark);

  const bool ordered = landmark.format_version >= 2;
  LeafOrderPoints read = read_points(grid, path, ordered, views, colours);
  if (ordered) {
    restore_capture_order(read, views, colours, path, landmark);
  } else {
    landmark.points.points = std::move(read.positions);
  }
  landmark.points.set_unorganized();
  landmark.points.T_cloud_sensor.translation() = landmark.sensor_origin;
  return landmark;
}

template <typename GridT>
typename GridT::Ptr read_grid(vdb::io::File& file, const std::string& name,
                              const std::string& path) {
  if (!file.hasGrid(name)) {
    throw Error(path + ": landmark file of version 2 lacks its '" + name + "' grid");
  }
  auto grid = vdb::GridBase::grid<GridT>(file.readGrid(name));
  if (!grid) throw Error(path + ": the '" + name + "' grid has the wrong type");
  return grid;
}

// Everything that must hold before OpenVDB may open the file: it exists, is an OpenVDB file, and
// its lmk trailer matches its data.
void check_landmark_file(const std::string& path) {
  const std::string bytes = read_input_file(path, kLandmarkInput);
  if (!has_vdb_magic(bytes)) throw Error(path + ": not an lmk landmark file (not an OpenVDB file)");
  detail::check_landmark_trailer(path, bytes);
  detail::check_vdb_layout(path, bytes.substr(0, bytes.size() - detail::kLandmarkTrailerSize));
}

// Runs `read` on the landmark file at `path`, opened once check_landmark_file() has passed:
// OpenVDB must never see a damaged file. What OpenVDB throws on a file written wrong behind a valid
// checksum becomes one lmk::Error naming the file.
template <class Read>
auto read_landmark_file(const std::string& path, bool delay_load, Read&& read) {
  check_landmark_file(path);
  vdb::initialize();  // idempotent: registers OpenVDB's grid and metadata types once per process
  try {
    vdb::io::File file(path);
    file.open(delay_load);
    return read(file);
  } catch (const vdb::Exception& e) {
    throw Error(path + ": corrupt or truncated landmark file (" + e.what() + ")");
  } catch (const std::ios_base::failure& e) {
    throw Error(path + ": corrupt or truncated landmark file (" + e.what() + ")");
  } catch (const std::bad_alloc&) {
    throw corrupt_sizes(path);
  } catch (const std::length_error&) {
    throw corrupt_sizes(path);
  }
}

void require_points_grid(const vdb::io::File& file, const std::string& path) {
  if (!file.hasGrid(kPointsGrid)) {
    throw Error(path + ": not an lmk landmark file: it has no '" + std::string(kPointsGrid) +
                "' grid");
  }
}

// The findings a file of format 4 stores, parsed; absent otherwise.
void read_findings(const vdb::points::PointDataGrid& grid, const std::string& path,
                   Landmark& landmark) {
  const auto meta = grid.getMetadata<vdb::StringMetadata>(kFindingsMeta);
  if (!meta) return;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(meta->value());
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": corrupt landmark file: " + kFindingsMeta + " is not JSON (" + e.what() +
                ")");
  }
  landmark.findings = capture_findings_from_json(j, path + ": " + kFindingsMeta);
}

}  // namespace

bool has_vdb_magic(const std::string& bytes) {
  return bytes.size() >= 8 && bytes.compare(0, 4, "\x20\x42\x44\x56") == 0;
}

Landmark read_vdb_landmark(const std::string& path) {
  return read_landmark_file(path, /*delay_load=*/false, [&](vdb::io::File& file) {
    require_points_grid(file, path);
    const auto grid = vdb::GridBase::grid<vdb::points::PointDataGrid>(file.readGrid(kPointsGrid));
    if (!grid) throw Error(path + ": not an lmk landmark file: 'points' is not a point grid");
    Landmark landmark = landmark_from_grid(*grid, path);
    read_findings(*grid, path, landmark);
    if (landmark.format_version >= 2) {
      EmptySpaceGrid::Grid empty;
      empty.grid = read_grid<vdb::BoolGrid>(file, "empty", path);
      landmark.empty_space = EmptySpaceGrid::from_grid(std::move(empty));
    }
    file.close();
    return landmark;
  });
}

int read_vdb_landmark_version(const std::string& path) {
  return read_landmark_file(path, /*delay_load=*/true, [&](vdb::io::File& file) {
    require_points_grid(file, path);
    const vdb::GridBase::Ptr grid = file.readGridMetadata(kPointsGrid);
    file.close();
    return require_meta<vdb::Int32Metadata>(*grid, "lmk_format_version", path);
  });
}

void write_vdb_landmark(const std::string& path, const Landmark& landmark) {
  vdb::initialize();  // idempotent: registers OpenVDB's grid and metadata types once per process
  const auto grid = make_points_grid(landmark);
  const DistanceField::Grids& field = landmark.distance.grids();
  const vdb::GridPtrVec grids = {grid, field.distance, field.closest,
                                 landmark.empty_space.grid().grid};
  write_file_atomically(path, [&](const fs::path& tmp) {
    try {
      vdb::io::File file(tmp.string());
      file.write(grids);
      file.close();
    } catch (const vdb::Exception& e) {
      throw Error(path + ": cannot write the landmark file: " + e.what());
    }
    append_trailer(tmp);
  });
}

}  // namespace lmk::detail
