// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/landmark_file.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/detail/landmark_container.h"
#include "lmk/landmark/detail/landmark_record.h"
#include "lmk/landmark/detail/vdb_landmark_file.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// The scene, box and settings of the sample landmarks.
PointCloud sample_scene() {
  PointCloud scene = test::random_cloud(100000, 3, 0.4f);
  scene.T_cloud_sensor.translation() << 0.1, -0.2, -1.5;
  return scene;
}

const Box kSampleBox(pose_from_xyz_rpy({0.05, 0.0, 0.1}, {0.3, -0.2, 1.0}), {0.2, 0.3, 0.1});

CaptureSettings sample_settings() {
  CaptureSettings settings;
  settings.leaf_size = 0.01;
  settings.min_points = 40;
  return settings;
}

Landmark sample_landmark() {
  return capture(sample_scene(), kSampleBox, "test landmark", sample_settings());
}

// The same cut from the same scene, seen again from a second pose 2 cm and 3 degrees away.
Landmark sample_two_view_landmark() {
  const PointCloud scene = sample_scene();
  return capture_views({{&scene, Eigen::Isometry3d::Identity()},
                        {&scene, pose_from_xyz_rpy({0.02, 0.0, 0.0}, {0.0, 0.05, 0.0})}},
                       kSampleBox, "two views", sample_settings());
}

std::vector<Eigen::Vector3f> sorted(std::vector<Eigen::Vector3f> v) {
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return v;
}

void expect_same(const Landmark& a, const Landmark& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.format_version, b.format_version);
  EXPECT_TRUE(a.box.pose.isApprox(b.box.pose, 1e-12));
  EXPECT_EQ(a.box.size, b.box.size);
  EXPECT_EQ(a.sensor_origin, b.sensor_origin);
  EXPECT_EQ(a.settings.leaf_size, b.settings.leaf_size);
  EXPECT_EQ(a.settings.min_points, b.settings.min_points);
  EXPECT_EQ(a.settings.max_box_side, b.settings.max_box_side);
  // The file may store points in another order, but every coordinate is bit-exact.
  EXPECT_EQ(sorted(a.points.points), sorted(b.points.points));
}

TEST(LandmarkFile, RoundTripIsLossless) {
  test::ScratchDir dir;
  const Landmark original = sample_landmark();
  save_landmark(dir.file("a.lmk"), original);
  const Landmark loaded = load_landmark(dir.file("a.lmk"));
  expect_same(original, loaded);
  EXPECT_EQ(landmark_file_version(dir.file("a.lmk")), kLandmarkFormatVersion);
  // Format 5 keeps the capture order and the empty space voxel for voxel, and rebuilds the
  // distance field from the points as the capture built it.
  EXPECT_EQ(loaded.points.points, original.points.points);
  EXPECT_EQ(loaded.empty_space.voxels(), original.empty_space.voxels());
  const auto rebuilt = loaded.distance.sampler(), built = original.distance.sampler();
  for (const Eigen::Vector3f& c : original.empty_space.centres()) {
    EXPECT_EQ(rebuilt.distance(c), built.distance(c));
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), {}), 1);  // no temporary left
}

// The stored closest-point grid indexes the points: after loading, for the voxel centre nearest to
// each landmark point it must name a point at exactly the brute-force nearest distance, whatever
// order the file keeps the points in.
TEST(LandmarkFile, LoadedDistanceFieldIndexesTheLoadedPoints) {
  test::ScratchDir dir;
  save_landmark(dir.file("a.lmk"), sample_landmark());
  const Landmark loaded = load_landmark(dir.file("a.lmk"));
  const auto field = loaded.distance.sampler();
  const auto& points = loaded.points.points;
  const float leaf = static_cast<float>(loaded.settings.leaf_size);
  for (const auto& p : points) {
    const Eigen::Vector3f centre = (p / leaf).array().round().matrix() * leaf;
    float nearest = std::numeric_limits<float>::infinity();
    for (const auto& q : points) nearest = std::min(nearest, (q - centre).norm());
    const int index = field.closest(p);
    ASSERT_GE(index, 0);
    EXPECT_NEAR((points[static_cast<std::size_t>(index)] - centre).norm(), nearest, 1e-6);
  }
}

TEST(LandmarkFile, ExportImportRoundTrip) {
  test::ScratchDir dir;
  const Landmark original = sample_landmark();
  export_landmark(original, dir.file("out"));
  EXPECT_TRUE(fs::exists(dir.file("out/points.pcd")));
  EXPECT_TRUE(fs::exists(dir.file("out/landmark.json")));
  expect_same(original, import_landmark(dir.file("out")));
}

std::string load_error(const std::string& path) {
  try {
    load_landmark(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "loading " << path << " did not fail";
  return "";
}

TEST(LandmarkFile, BadFilesGiveClearErrors) {
  test::ScratchDir dir;
  EXPECT_NE(load_error(dir.file("missing.lmk")).find("no such file"), std::string::npos);
  // A point cloud renamed .lmk: a file of another format.
  write_cloud(dir.file("cloud.lmk.pcd"), test::random_cloud(10, 1));
  fs::rename(dir.file("cloud.lmk.pcd"), dir.file("cloud.lmk"));
  EXPECT_NE(load_error(dir.file("cloud.lmk")).find("neither format 5 nor an OpenVDB file"),
            std::string::npos);
  // Truncated: every prefix of a real file is refused, never a crash.
  save_landmark(dir.file("a.lmk"), sample_landmark());
  const std::string bytes = test::read_bytes(dir.file("a.lmk"));
  // 40 cut points across the file, and the last byte: each is refused with the file's name.
  std::vector<std::size_t> cuts = {bytes.size() - 1};
  for (std::size_t k = 1; k <= 40; ++k) cuts.push_back(bytes.size() * k / 41);
  for (const std::size_t keep : cuts) {
    test::write_text(dir.file("cut.lmk"), bytes.substr(0, keep));
    EXPECT_NE(load_error(dir.file("cut.lmk")).find(dir.file("cut.lmk")), std::string::npos) << keep;
  }
}

TEST(LandmarkFile, ForeignOpenVdbFileIsRefused) {
  test::ScratchDir dir;
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create();
  grid->setName("density");
  openvdb::io::File(dir.file("density.lmk")).write({grid});
  EXPECT_NE(load_error(dir.file("density.lmk")).find("OpenVDB file that lmk did not write"),
            std::string::npos);
}

// Every file lmk wrote before format 5 still loads, with what it held (its grids are decoded in a
// child process), and `lmk landmark upgrade` rewrites it in format 5 without changing it.
TEST(LandmarkFile, OldFormatsLoadAndUpgradeUnchanged) {
  test::ScratchDir dir;
  Landmark with_findings = sample_landmark();
  with_findings.findings.present = true;
  with_findings.findings.look_alikes = 3;
  with_findings.findings.look_alike_checked = true;
  const std::vector<std::pair<Landmark, int>> cases = {
      {sample_landmark(), 2}, {sample_two_view_landmark(), 3}, {with_findings, 4}};
  for (const auto& [original, version] : cases) {
    const std::string file = dir.file("v" + std::to_string(version) + ".lmk");
    detail::write_vdb_landmark(file, original);
    EXPECT_EQ(landmark_file_version(file), version);
    for (int pass = 0; pass < 2; ++pass) {  // as written, then upgraded
      const Landmark loaded = load_landmark(file);
      expect_same(original, loaded);
      EXPECT_EQ(loaded.points.points, original.points.points);
      EXPECT_EQ(loaded.point_views, original.point_views);
      EXPECT_EQ(loaded.empty_space.voxels(), original.empty_space.voxels());
      EXPECT_EQ(loaded.findings.look_alikes, original.findings.look_alikes);
      EXPECT_EQ(upgrade_landmark_file(file), pass == 0 ? version : kLandmarkFormatVersion);
    }
    EXPECT_EQ(landmark_file_version(file), kLandmarkFormatVersion);
  }
}

// Issue #61, finding 2: behind a valid checksum, a format-5 file is parsed by lmk whole. What does
// not fit its own counts, or would mean what no capture saw, is refused in one line; what loads is
// what the file says, its distance field rebuilt from its points.
TEST(LandmarkFile, AForgedFormat5FileIsRefusedOrMeansWhatItSays) {
  test::ScratchDir dir;
  save_landmark(dir.file("a.lmk"), sample_landmark());
  std::string data = test::read_bytes(dir.file("a.lmk"));
  data.resize(data.size() - detail::kLandmarkTrailerSize);
  detail::LandmarkRecord record = detail::parse_record("a.lmk", data);
  const auto error_of = [&](const detail::LandmarkRecord& r, const std::string& tail = "") {
    const std::string bytes = detail::record_bytes(r) + tail;
    test::write_text(dir.file("forged.lmk"), bytes + detail::landmark_trailer(bytes));
    return load_error(dir.file("forged.lmk"));
  };
  EXPECT_NE(error_of(record, "extra").find("do not fill its"), std::string::npos);
  detail::LandmarkRecord far = record;
  far.empty_voxels.back() = Eigen::Vector3i(1000, 1000, 1000);
  EXPECT_NE(error_of(far).find("an empty-space voxel lies outside the box"), std::string::npos);
  detail::LandmarkRecord on_surface = record;
  on_surface.empty_voxels = {(record.points[0] / 0.01f).array().round().cast<int>().matrix()};
  EXPECT_NE(error_of(on_surface).find("an empty-space voxel lies on the landmark's surface"),
            std::string::npos);
  detail::LandmarkRecord unordered = record;
  std::swap(unordered.empty_voxels.front(), unordered.empty_voxels.back());
  EXPECT_NE(error_of(unordered).find("not in ascending order"), std::string::npos);
  detail::LandmarkRecord nan = record;
  nan.points[3].x() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(error_of(nan).find("a point is not finite"), std::string::npos);
  detail::LandmarkRecord views = record;
  views.views.assign(views.points.size(), 2u);  // a second view the header does not have
  EXPECT_NE(error_of(views).find("point views without the views"), std::string::npos);
  detail::LandmarkRecord leaf = record;
  leaf.header["capture"]["leaf_size"] = 1e-9;
  EXPECT_NE(error_of(leaf).find("leaf_size"), std::string::npos);
  // The header's length and JSON.
  std::string bad_json = data;
  bad_json[16] = '[';
  test::write_text(dir.file("json.lmk"), bad_json + detail::landmark_trailer(bad_json));
  EXPECT_NE(load_error(dir.file("json.lmk")).find("its header is not JSON"), std::string::npos);
  std::string long_header = data;
  const std::uint32_t huge = 0xfffffff0u;
  std::memcpy(&long_header[12], &huge, sizeof(huge));
  test::write_text(dir.file("long.lmk"), long_header + detail::landmark_trailer(long_header));
  EXPECT_NE(load_error(dir.file("long.lmk")).find("a header of 4294967280 bytes"),
            std::string::npos);
  // Moved points with their free space moved off them load as such: the distance field follows the
  // points. Moved alone, their old free space touches them: refused above.
  detail::LandmarkRecord moved = record;
  for (Eigen::Vector3f& p : moved.points) p.z() += 0.001f;
  EXPECT_NE(error_of(moved).find("lies on the landmark's surface"), std::string::npos);
  moved.empty_voxels.clear();
  const std::string bytes = detail::record_bytes(moved);
  test::write_text(dir.file("moved.lmk"), bytes + detail::landmark_trailer(bytes));
  const Landmark loaded = load_landmark(dir.file("moved.lmk"));
  EXPECT_EQ(loaded.points.points, moved.points);
  const DistanceField expected(moved.points,
                               {loaded.settings.leaf_size, loaded.settings.distance_band});
  for (const Eigen::Vector3f& p : moved.points) {
    EXPECT_EQ(loaded.distance.sampler().distance(p), expected.sampler().distance(p));
  }
}

TEST(LandmarkFile, FlippedByteIsCaught) {
  test::ScratchDir dir;
  save_landmark(dir.file("a.lmk"), sample_landmark());
  std::string bytes = test::read_bytes(dir.file("a.lmk"));
  bytes[bytes.size() / 2] ^= 0x10;
  test::write_text(dir.file("a.lmk"), bytes);
  EXPECT_NE(load_error(dir.file("a.lmk")).find("does not match the checksum"), std::string::npos);
}

// Behind a valid checksum, a length that OpenVDB would trust is checked against the bytes first:
// a metadata string declared 4 GB long made OpenVDB allocate 18 GB and take a minute.
TEST(LandmarkFile, DeclaredLengthsAreCheckedBeforeOpenVdbReadsThem) {
  test::ScratchDir dir;
  detail::write_vdb_landmark(dir.file("a.lmk"), sample_landmark());
  std::string data = test::read_bytes(dir.file("a.lmk"));
  data.resize(data.size() - detail::kLandmarkTrailerSize);
  // The name's metadata entry: "lmk_name", its type "string" (a 32-bit length first), then the
  // value's 32-bit length. The pattern holds NULs, so it is built with its length.
  const std::string entry("lmk_name\x06\x00\x00\x00string", 18);
  const std::size_t name = data.find(entry);
  ASSERT_NE(name, std::string::npos);
  const std::size_t length_at = name + entry.size();
  for (const std::uint32_t length : {0xfffffff0u, 0x7fffffffu}) {
    std::string bad = data;
    std::memcpy(&bad[length_at], &length, sizeof(length));
    test::write_text(dir.file("bad.lmk"), bad + detail::landmark_trailer(bad));
    EXPECT_NE(
        load_error(dir.file("bad.lmk")).find("grid metadata declares more bytes than the file"),
        std::string::npos)
        << load_error(dir.file("bad.lmk"));
  }
  // The same file resealed unchanged still loads: the walk accepts what OpenVDB writes.
  test::write_text(dir.file("same.lmk"), data + detail::landmark_trailer(data));
  EXPECT_EQ(load_landmark(dir.file("same.lmk")).name, "test landmark");
}

TEST(LandmarkFile, ImportValidates) {
  test::ScratchDir dir;
  export_landmark(sample_landmark(), dir.file("out"));
  std::ifstream in(dir.file("out/landmark.json"));
  std::string json((std::istreambuf_iterator<char>(in)), {});
  const std::size_t q = json.find("\"quaternion\"");
  ASSERT_NE(q, std::string::npos);
  // Scale the quaternion's first component: no longer a unit quaternion.
  const std::size_t first = json.find_first_of("-0123456789", json.find('[', q));
  json.insert(first, "3");
  test::write_text(dir.file("out/landmark.json"), json);
  try {
    import_landmark(dir.file("out"));
    ADD_FAILURE() << "import accepted a bad quaternion";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a unit quaternion"), std::string::npos) << e.what();
  }
  EXPECT_THROW(import_landmark(dir.file("nowhere")), Error);
}

// Issue #47: a landmark's name is printed by every command that shows it; one with a control
// character is neither written nor read.
TEST(LandmarkFile, ANameWithAControlCharacterIsRefused) {
  test::ScratchDir dir;
  Landmark landmark = sample_landmark();
  landmark.name = "milk\x1b]0;pwned\x07";
  try {
    save_landmark(dir.file("bad.lmk"), landmark);
    ADD_FAILURE() << "saved";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("landmark name 'milk\\x1b]0;pwned\\x07' is not printable"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.lmk")));
  // Nor through landmark.json, whatever wrote it.
  export_landmark(sample_landmark(), dir.file("out"));
  std::ifstream in(dir.file("out/landmark.json"));
  std::string json((std::istreambuf_iterator<char>(in)), {});
  const std::string name = "\"name\": \"" + sample_landmark().name + "\"";
  ASSERT_NE(json.find(name), std::string::npos);
  json.replace(json.find(name), name.size(), "\"name\": \"a\\u009bb\"");
  test::write_text(dir.file("out/landmark.json"), json);
  EXPECT_THROW(import_landmark(dir.file("out")), Error);
}

}  // namespace
}  // namespace lmk

namespace lmk {
namespace {

// A file of several views, damaged or written wrong behind a valid checksum, is refused with one
// line; whole, it comes back with its views.
TEST(LandmarkFile, ViewsAreReadBackAndCheckedBehindAValidChecksum) {
  test::ScratchDir dir;
  const Landmark original = sample_two_view_landmark();
  detail::write_vdb_landmark(dir.file("a.lmk"), original);  // format 3: views in OpenVDB metadata
  const Landmark loaded = load_landmark(dir.file("a.lmk"));
  EXPECT_EQ(loaded.view_origins, original.view_origins);
  EXPECT_EQ(loaded.point_views, original.point_views);
  std::string bytes = test::read_bytes(dir.file("a.lmk"));
  bytes[bytes.size() / 2] ^= 0x10;
  test::write_text(dir.file("flipped.lmk"), bytes);
  EXPECT_NE(load_error(dir.file("flipped.lmk")).find("does not match the checksum"),
            std::string::npos);
  // The view count's metadata entry: its name, its type "int32", the value's 32-bit length (4),
  // then the value.
  std::string data = test::read_bytes(dir.file("a.lmk"));
  data.resize(data.size() - detail::kLandmarkTrailerSize);
  const std::string entry("lmk_view_count\x05\x00\x00\x00int32", 23);
  const std::size_t at = data.find(entry);
  ASSERT_NE(at, std::string::npos);
  for (const std::int32_t count : {1, 17, 3}) {
    std::string bad = data;
    std::memcpy(&bad[at + entry.size() + 4], &count, sizeof(count));
    test::write_text(dir.file("bad.lmk"), bad + detail::landmark_trailer(bad));
    const std::string error = load_error(dir.file("bad.lmk"));
    EXPECT_NE(error.find(count == 3 ? "lmk_view_origin_2" : std::to_string(count) + " views"),
              std::string::npos)
        << error;
  }
}

}  // namespace
}  // namespace lmk
