// SPDX-License-Identifier: BSD-3-Clause
// The pose list of fused frames (pose_list.h): TUM's order with or without its timestamp, comments
// and blank lines, and one line naming what is wrong with a bad pose.

#include "lmk/geometry/pose_list.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lmk/geometry/error.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

std::string pose_list_error(const std::string& text) {
  return test::error_of([&] { parse_pose_list(text, "poses.txt"); });
}

TEST(PoseList, ReadsTumOrderWithOrWithoutATimestamp) {
  const auto poses = parse_pose_list(
      "# x y z qx qy qz qw\n"
      "1 2 3 0 0 0 1\n"
      "\n"
      "1305031102.175304 0.5 0 0 0 0 0.7071068 0.7071068  # turned 90 degrees about z\n",
      "poses.txt");
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_TRUE(poses[0].translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(poses[0].linear().isIdentity(1e-12));
  EXPECT_TRUE(poses[1].translation().isApprox(Eigen::Vector3d(0.5, 0, 0)));
  EXPECT_TRUE(
      (poses[1].linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-6));
}

TEST(PoseList, BadLinesAreRefusedWithTheirNumber) {
  EXPECT_EQ(
      pose_list_error("0 0 0 0 0 0 1\n1 2 3\n"),
      "poses.txt:2: expected 7 numbers (x y z qx qy qz qw) or 8 (a timestamp first), found 3");
  EXPECT_EQ(pose_list_error("0 0 x 0 0 0 1\n"), "poses.txt:1: 'x' is not a number");
  // Issue #61, finding 11: a NUL (or an escape) in a field is shown, not sent: the message is
  // whole as a C string.
  const std::string nul = pose_list_error(std::string("0 0 1\0x 0 0 0 1\n", 16));
  EXPECT_EQ(std::string(nul.c_str()), "poses.txt:1: '1\\x00x' is not a number");
  EXPECT_NE(
      pose_list_error("0 0 0 0 0 0 2\n").find("poses.txt:1.quaternion: is not a unit quaternion"),
      std::string::npos)
      << pose_list_error("0 0 0 0 0 0 2\n");
  EXPECT_NE(pose_list_error("0 0 nan 0 0 0 1\n").find("poses.txt:1"), std::string::npos);
  EXPECT_NE(pose_list_error("1e308 0 0 0 0 0 1\n").find("at most 10000 m"), std::string::npos);
  EXPECT_EQ(pose_list_error(""), "");
  EXPECT_TRUE(parse_pose_list("# nothing\n\n", "poses.txt").empty());
}

// Issue #61, finding 5: a pose list is a pose a frame; one over 1 MiB is refused by its size
// before it is read (a 266 MB list took 4.7 GB as it was parsed). A sparse file: nothing is read.
TEST(PoseList, AFileOverAMebibyteIsRefusedUnread) {
  const test::ScratchDir dir;
  const std::string path = dir.file("poses.txt");
  std::ofstream(path).close();
  std::filesystem::resize_file(path, std::uintmax_t{266} << 20);
  try {
    read_pose_list(path);
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("for a pose list"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lmk
