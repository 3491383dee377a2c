// SPDX-License-Identifier: BSD-3-Clause
// An SRDF's <disable_collisions> pairs (pr2/srdf.h) make links that touch by design exempt from
// the self-collision check, as the links near each other along the tree are; bad SRDFs are refused
// naming what is wrong, and the real PR2 package's SRDF reads (skipped without ../shared).

#include "lmk/pr2/srdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "lmk/geometry/error.h"
#include "lmk/pr2/robot_body.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// The index of `link` among the body's links.
std::size_t link_index(const RobotBody& body, const std::string& link) {
  std::size_t i = 0;
  while (i < body.links().size() && body.links()[i] != link) ++i;
  EXPECT_LT(i, body.links().size()) << link;
  return i;
}

const char* const kTwoPalms = R"(<?xml version="1.0"?>
<robot name="pr2">
  <group name="right_arm"/>
  <disable_collisions link1="r_gripper_palm_link" link2="l_gripper_palm_link" reason="Never"/>
  <disable_collisions link1="r_shoulder_pan_link" link2="r_shoulder_lift_link" reason="Adjacent"/>
</robot>)";

TEST(Srdf, DisabledPairsAreReadInOrder) {
  const std::vector<LinkPair> pairs = srdf_disabled_collisions(kTwoPalms, "test");
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], LinkPair("r_gripper_palm_link", "l_gripper_palm_link"));
  EXPECT_EQ(pairs[1], LinkPair("r_shoulder_pan_link", "r_shoulder_lift_link"));
}

TEST(Srdf, APairItNamesMayTouchAndNoOtherDoes) {
  const auto model = std::make_shared<RobotModel>(RobotModel::pr2());
  const RobotBody plain(model);
  const RobotBody semantic(model, {}, 0.015, srdf_disabled_collisions(kTwoPalms, "test"));
  const std::size_t r = link_index(plain, "r_gripper_palm_link"),
                    l = link_index(plain, "l_gripper_palm_link"),
                    f = link_index(plain, "l_forearm_link");
  EXPECT_FALSE(plain.may_touch(r, l));
  EXPECT_TRUE(semantic.may_touch(r, l));
  EXPECT_TRUE(semantic.may_touch(l, r));
  EXPECT_FALSE(semantic.may_touch(r, f));
}

TEST(Srdf, BadDescriptionsAreRefusedSayingWhy) {
  EXPECT_THROW(srdf_disabled_collisions("<robot", "x"), Error);
  try {
    srdf_disabled_collisions("<model/>", "semantic");
    FAIL() << "a root other than <robot> was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("semantic: not an SRDF"), std::string::npos) << e.what();
  }
  try {
    srdf_disabled_collisions("<robot>\n<disable_collisions link1=\"a\"/></robot>", "semantic");
    FAIL() << "a pair without link2 was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2) lacks link1 or link2"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(srdf_disabled_collisions_file("/nonexistent/robot.srdf"), Error);
  // A pair naming a link the robot lacks: the SRDF is for another robot.
  const auto model = std::make_shared<RobotModel>(RobotModel::pr2());
  EXPECT_THROW(RobotBody(model, {}, 0.015, {{"r_gripper_palm_link", "tail_link"}}), Error);
}

TEST(Srdf, TheRealPr2PackagesSrdfReads) {
  LMK_REQUIRE_SHARED_DATA(data);
  const std::vector<LinkPair> all =
      srdf_disabled_collisions_file((data / "robots" / "pr2" / "robot.srdf").string());
  ASSERT_FALSE(all.empty());
  // The package describes the whole PR2; lmk's description is its arms and body.
  const auto model = std::make_shared<RobotModel>(RobotModel::pr2());
  std::vector<LinkPair> pairs;
  for (const LinkPair& p : all)
    if (model->has_link(p.first) && model->has_link(p.second)) pairs.push_back(p);
  ASSERT_FALSE(pairs.empty());
  const RobotBody body(model, {}, 0.015, pairs);
  for (const auto& [a, b] : pairs) {
    bool both = true;
    for (const std::string& link : {a, b})
      both =
          both && std::find(body.links().begin(), body.links().end(), link) != body.links().end();
    if (both) {
      EXPECT_TRUE(body.may_touch(link_index(body, a), link_index(body, b))) << a << b;
    }
  }
}

}  // namespace
}  // namespace lmk
