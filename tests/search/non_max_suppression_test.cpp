// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/non_max_suppression.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

TEST(NonMaxSuppression, KeepsTheBestOfEachNeighbourhoodSortedByError) {
  const std::vector<Eigen::Vector3d> centres = {{0, 0, 0},    {0.01, 0, 0},
                                                {0.02, 0, 0},                 // one cluster
                                                {1, 0, 0},    {1.005, 0, 0},  // another
                                                {2, 0, 0}};                   // alone
  const std::vector<double> errors = {0.003, 0.001, 0.004, 0.002, 0.005, 0.009};
  EXPECT_EQ(non_max_suppression(centres, errors, 0.03), (std::vector<std::size_t>{1, 3, 5}));
}

TEST(NonMaxSuppression, LiteralRuleAndDeterministicTies) {
  // A chain a - b - c, 2 cm apart, errors increasing. Literally, c is removed by b, which lies
  // within 3 cm and is better, even though b is itself removed by a. (Greedy suppression, which
  // only lets kept candidates suppress, would keep c.)
  const std::vector<Eigen::Vector3d> centres = {{0, 0, 0}, {0.02, 0, 0}, {0.04, 0, 0}};
  EXPECT_EQ(non_max_suppression(centres, {0.001, 0.002, 0.003}, 0.03),
            (std::vector<std::size_t>{0}));
  // Equal errors: the lower index wins.
  EXPECT_EQ(non_max_suppression({{0, 0, 0}, {0.001, 0, 0}}, {0.002, 0.002}, 0.03),
            (std::vector<std::size_t>{0}));
  EXPECT_THROW(non_max_suppression({{0, 0, 0}}, {}, 0.03), Error);
}

// A 20 x 10 x 10 cm box centred at (x, y, 0), turned `yaw` about z.
Box flat_box_at(double x, double y, double yaw = 0.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, 0.0);
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return Box(pose, Eigen::Vector3d(0.2, 0.1, 0.1));
}

TEST(ExclusiveBoxes, AMatchInsideABetterMatchsBoxIsTheSameObject) {
  // Best first: 1 lies in 0's box (5 cm off along its long side, beyond the 3 cm non-max radius);
  // 2 stands beside 0, touching but outside; 3 lies in 2's box.
  const std::vector<Box> boxes = {flat_box_at(0, 0), flat_box_at(0.05, 0), flat_box_at(0, 0.11),
                                  flat_box_at(0.02, 0.12)};
  EXPECT_EQ(exclusive_boxes(boxes), (std::vector<std::size_t>{0, 2}));
}

TEST(ExclusiveBoxes, OnlyKeptMatchesSuppressAndTheBoxesAreOriented) {
  // 1 lies in 0's box and goes; 2 lies in 1's box but not in 0's, and stays.
  EXPECT_EQ(exclusive_boxes({flat_box_at(0, 0), flat_box_at(0.09, 0), flat_box_at(0.18, 0)}),
            (std::vector<std::size_t>{0, 2}));
  // 8 cm along y is outside a box 10 cm deep, inside the same box turned a quarter turn.
  EXPECT_EQ(exclusive_boxes({flat_box_at(0, 0), flat_box_at(0, 0.08)}),
            (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(exclusive_boxes({flat_box_at(0, 0, M_PI / 2), flat_box_at(0, 0.08)}),
            (std::vector<std::size_t>{0}));
  EXPECT_TRUE(exclusive_boxes({}).empty());
}

}  // namespace
}  // namespace lmk
