// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/non_max_suppression.h"

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

}  // namespace
}  // namespace lmk
