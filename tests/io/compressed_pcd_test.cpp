// SPDX-License-Identifier: BSD-3-Clause
// Issue #61, finding 1: a compressed PCD is read by lmk, keeping only the fields it reads as the
// LZF stream goes by, so that what a file costs follows the points it holds and not what its
// header declares of fields nobody reads.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <cstring>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/random.h"
#include "tests/support/test_support.h"

namespace lmk::test {
namespace {

void add_field(pcl::PCLPointCloud2& blob, const std::string& name, std::uint8_t type,
               std::uint32_t count) {
  pcl::PCLPointField f;
  f.name = name;
  f.offset = blob.point_step;
  f.datatype = type;
  f.count = count;
  blob.fields.push_back(f);
  blob.point_step += count * static_cast<std::uint32_t>(pcl::getFieldSize(type));
}

// An organised 7 x 5 blob with fields lmk reads between fields it does not: a 33-value
// descriptor, a double y, padding, an integer label; random bytes where no number is needed.
pcl::PCLPointCloud2 mixed_blob() {
  using F = pcl::PCLPointField;
  pcl::PCLPointCloud2 blob;
  blob.width = 7;
  blob.height = 5;
  add_field(blob, "intensity", F::FLOAT32, 1);
  add_field(blob, "x", F::FLOAT32, 1);
  add_field(blob, "y", F::FLOAT64, 1);
  add_field(blob, "descriptor", F::FLOAT32, 33);
  add_field(blob, "z", F::FLOAT32, 1);
  add_field(blob, "normal_x", F::FLOAT32, 1);
  add_field(blob, "normal_y", F::FLOAT32, 1);
  add_field(blob, "normal_z", F::FLOAT32, 1);
  add_field(blob, "rgb", F::FLOAT32, 1);
  add_field(blob, "label", F::UINT32, 1);
  blob.row_step = blob.point_step * blob.width;
  blob.data.resize(std::size_t{blob.row_step} * blob.height);
  SplitMix64 rng(61);
  for (std::uint8_t& b : blob.data) b = static_cast<std::uint8_t>(rng.uniform_index(256));
  for (std::size_t i = 0; i < std::size_t{blob.width} * blob.height; ++i) {
    std::uint8_t* p = blob.data.data() + i * blob.point_step;
    const float x = static_cast<float>((2.0 * rng.uniform01() - 1.0)), z = static_cast<float>(i);
    const double y = (2.0 * rng.uniform01() - 1.0);
    std::memcpy(p + blob.fields[1].offset, &x, 4);
    std::memcpy(p + blob.fields[2].offset, &y, 8);
    std::memcpy(p + blob.fields[4].offset, &z, 4);
    for (int a = 5; a < 8; ++a) {
      const float n = static_cast<float>((2.0 * rng.uniform01() - 1.0));
      std::memcpy(p + blob.fields[a].offset, &n, 4);
    }
  }
  return blob;
}

TEST(CompressedPcd, ReadsWhatTheSameCloudUncompressedHolds) {
  ScratchDir dir;
  const pcl::PCLPointCloud2 blob = mixed_blob();
  const Eigen::Vector4f origin(0.5f, -1.0f, 2.0f, 0.0f);
  const Eigen::Quaternionf orientation(Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitZ()));
  pcl::PCDWriter writer;
  ASSERT_EQ(writer.writeBinary(dir.file("plain.pcd"), blob, origin, orientation), 0);
  ASSERT_EQ(writer.writeBinaryCompressed(dir.file("packed.pcd"), blob, origin, orientation), 0);

  const CloudFile plain = read_cloud_file(dir.file("plain.pcd"));
  const CloudFile packed = read_cloud_file(dir.file("packed.pcd"));
  EXPECT_EQ(packed.encoding, Encoding::kBinaryCompressed);
  EXPECT_EQ(packed.fields, plain.fields);
  EXPECT_EQ(packed.cloud.width, 7u);
  EXPECT_EQ(packed.cloud.height, 5u);
  ASSERT_EQ(packed.cloud.size(), plain.cloud.size());
  ASSERT_TRUE(packed.cloud.has_normals() && packed.cloud.has_colors() && packed.cloud.has_labels());
  for (std::size_t i = 0; i < plain.cloud.size(); ++i) {
    EXPECT_EQ(packed.cloud.points[i], plain.cloud.points[i]) << i;
    EXPECT_EQ(packed.cloud.normals[i], plain.cloud.normals[i]) << i;
    EXPECT_EQ(packed.cloud.colors[i].r, plain.cloud.colors[i].r) << i;
    EXPECT_EQ(packed.cloud.labels[i], plain.cloud.labels[i]) << i;
  }
  EXPECT_TRUE(packed.cloud.T_cloud_sensor.isApprox(plain.cloud.T_cloud_sensor, 1e-6));
  EXPECT_NEAR(packed.cloud.T_cloud_sensor.translation().x(), 0.5, 1e-6);
}

// The audit's bomb, smaller: 200,000 points of 4,012 bytes, 800 MB of zeros in a 9 MB file.
// PCL held every declared byte twice; lmk holds the 12 bytes a point it reads.
TEST(CompressedPcd, ABombOfFieldsNobodyReadsCostsOnlyWhatIsRead) {
  ScratchDir dir;
  const std::string path = dir.file("bomb.pcd");
  const std::size_t points = 200'000, expanded = points * 4 * 1003;
  const std::size_t file_bytes = write_zero_compressed_pcd(path, points, {"x", "y", "z"}, 1000);
  const std::optional<DeclaredCloud> declared = declared_cloud(path);
  ASSERT_TRUE(declared);
  EXPECT_EQ(declared->points, points);
  EXPECT_EQ(declared->decoded_point_bytes, 12u);  // x, y and z: the pad is never kept

  if (!reset_peak_memory()) GTEST_SKIP() << "/proc/self/clear_refs cannot be written here";
  const double before = process_status_bytes("VmRSS");
  const CloudFile file = read_cloud_file(path);
  const double peak = process_status_bytes("VmHWM") - before;
  EXPECT_EQ(file.cloud.size(), points);
  EXPECT_EQ(file.fields, (std::vector<std::string>{"x", "y", "z", "pad"}));
  std::printf("%zu-byte file expanding to %zu bytes: reading it took %.1f MB\n", file_bytes,
              expanded, peak / 1e6);
  // The file read whole, the kept fields and the cloud: a few times the file, never the expansion.
  EXPECT_LT(peak, 4.0 * static_cast<double>(file_bytes) + 40.0 * points);
  EXPECT_LT(peak, static_cast<double>(expanded) / 20.0);
}

// A compressed PCD of one x/y/z point (12 bytes) whose LZF block is `block`.
std::string one_point_pcd(const std::string& block, std::uint32_t expanded = 12) {
  const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(block.size()), expanded};
  std::string bytes =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA binary_compressed\n";
  bytes.append(reinterpret_cast<const char*>(sizes), sizeof(sizes));
  return bytes + block;
}

TEST(CompressedPcd, CorruptBlocksAreRefusedInOneLine) {
  ScratchDir dir;
  const auto refusal = [&](const std::string& name, const std::string& bytes) {
    write_text(dir.file(name), bytes);
    try {
      read_cloud(dir.file(name));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  const std::string twelve_zeros = std::string("\x0b", 1) + std::string(12, '\0');
  EXPECT_EQ(refusal("good.pcd", one_point_pcd(twelve_zeros)), "read");
  EXPECT_NE(refusal("early.pcd", one_point_pcd(std::string("\x20\x00", 2) + twelve_zeros))
                .find("a back reference points before the start of the data"),
            std::string::npos);
  EXPECT_NE(refusal("cut.pcd", one_point_pcd(std::string("\x0b\x00\x00", 3)))
                .find("a literal run is cut off by the end of the block"),
            std::string::npos);
  EXPECT_NE(refusal("long.pcd", one_point_pcd(twelve_zeros + std::string("\x00\x00", 2)))
                .find("expands past its declared size"),
            std::string::npos);
  EXPECT_NE(refusal("short.pcd", one_point_pcd(std::string("\x05", 1) + std::string(6, '\0')))
                .find("expands to 6 bytes, not the 12 it declares"),
            std::string::npos);
  EXPECT_NE(refusal("sizes.pcd", one_point_pcd(twelve_zeros, 24))
                .find("header declares 1 points but the data holds 2"),
            std::string::npos);
}

// Zeros are a valid cloud, and LZF repeats 264 bytes from 3: a compressed block whose kept points
// pass 256 MiB may expand at most 16-fold, so that no file under 25 MB takes a gigabyte to read.
TEST(CompressedPcd, ABlockThatWouldExpandPast16FoldIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("zeros.pcd");
  const std::size_t file_bytes = write_zero_compressed_pcd(path, 30'000'000, {"x", "y", "z"}, 0);
  ASSERT_LT(file_bytes, 5'000'000u);  // 360 MB of points in under 5 MB
  try {
    read_cloud(path);
    ADD_FAILURE() << "a 74-fold expansion was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("over 16 times its size"), std::string::npos) << e.what();
  }
  // A frame of mostly no returns expands far more than 16-fold, and is small: always read.
  const std::string blind = dir.file("blind.pcd");
  write_zero_compressed_pcd(blind, 640 * 480, {"x", "y", "z"}, 0);
  EXPECT_EQ(read_cloud(blind).size(), 640u * 480u);
}

}  // namespace
}  // namespace lmk::test
