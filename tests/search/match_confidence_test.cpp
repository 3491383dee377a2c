// SPDX-License-Identifier: BSD-3-Clause
// A match's confidence (match_confidence.h) on scenes built here, where the answer is known from
// the geometry alone: two identical objects are look-alikes of each other, a box cut out of a long
// beam slides along it, an L-shape alone on a table is pinned by its own corners, a flat patch
// of a table is the same patch wherever it lies on it, and a patch whose free space a post hides
// from the sensor is not confirmed free.

#include "lmk/search/confidence/match_confidence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "lmk/geometry/pose.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/landmark_index.h"
#include "lmk/search/metrics/sensor_metric.h"
#include "lmk/search/scene_index.h"
#include "lmk/sim/mesh.h"
#include "tests/landmark/l_shape_scene.h"

namespace lmk {
namespace {

using namespace test_scenes;

const MatchConfidence& only_match(const FindResult& r) {
  EXPECT_FALSE(r.matches.empty());
  return r.matches.front().confidence;
}

// The evidence in one line, for a failure's message.
std::string evidence(const MatchConfidence& c) {
  std::ostringstream out;
  out << "p " << c.probability << ", margins " << c.local_margin << " / " << c.elsewhere_margin
      << ", freedom " << c.freedom << (c.freest.turn ? " (turn)" : " (slide)") << ", competitor "
      << setting_name(c.competitor.kind) << " at " << c.competitor.distance << " m, "
      << c.competitor.angle << " rad, doubt '" << c.doubt << "'";
  return out.str();
}

TEST(MatchConfidence, TwoIdenticalObjectsAreEachOthersLookAlike) {
  const PointCloud scene = render_scene({kCopies[0], kCopies[1]}, false);
  const Landmark landmark = capture(scene, box_at(kCopies[0]), "L");
  const FindResult r = find_landmark(scene, landmark, FindSettings());
  ASSERT_EQ(r.matches.size(), 2u);
  const double apart = (box_at(kCopies[0]).center() - box_at(kCopies[1]).center()).norm();
  for (const Match& m : r.matches) {
    const MatchConfidence& c = m.confidence;
    EXPECT_EQ(c.competitor.kind, Competitor::Kind::look_alike);
    EXPECT_NEAR(c.competitor.distance, apart, 0.01);
    // The rival is the other copy, as good as this one within the noise: no clear winner.
    EXPECT_LT(std::abs(c.elsewhere_margin), 10.0);
    EXPECT_EQ(c.margin, c.elsewhere_margin);
    EXPECT_GE(c.probability, 0.0);
    EXPECT_LE(c.probability, 1.0);
  }
}

TEST(MatchConfidence, AnLShapeAloneHasNoRivalAndIsPinned) {
  const PointCloud scene = render_scene({kCopies[1]}, false);
  const Landmark landmark = capture(scene, box_at(kCopies[1]), "L");
  const FindResult r = find_landmark(scene, landmark, FindSettings());
  ASSERT_EQ(r.matches.size(), 1u);
  const MatchConfidence& c = only_match(r);
  SCOPED_TRACE(evidence(c));
  EXPECT_EQ(c.competitor.kind, Competitor::Kind::none);
  EXPECT_TRUE(std::isinf(c.margin));
  // Its corners fix it: along its freest motion the fit only worsens, so no probe is a rival.
  EXPECT_GT(c.support, 30u);
  EXPECT_NEAR(c.coverage, 1.0, 0.05);
  EXPECT_GT(c.probability, 0.8);
  EXPECT_TRUE(c.doubt.empty());
}

TEST(MatchConfidence, ABoxCutFromALongBeamSlidesAlongIt) {
  // A beam 80 cm long, 6 cm square, lying across the table along x; the box holds 20 cm of it,
  // with free space above and on its sides, and the beam going on through both of its ends.
  TriangleMesh beam;
  beam.append(make_box_mesh({0.8, 0.06, 0.06}),
              pose_from_xyz_rpy({0, 0, kTable + 0.03}, {0, 0, 0}));
  const PointCloud scene = render_on_table(beam);
  const Box box(pose_from_xyz_rpy({0.05, 0, kTable + 0.045}, {0, 0, 0}), {0.2, 0.1, 0.085});
  const Landmark landmark = capture(scene, box, "beam");
  const FindResult r = find_landmark(scene, landmark, FindSettings());
  ASSERT_FALSE(r.matches.empty());
  const MatchConfidence& c = only_match(r);
  SCOPED_TRACE(evidence(c));
  EXPECT_FALSE(c.freest.turn);
  EXPECT_GT(std::abs(c.freest.axis.x()), 0.95);  // free along the beam
  EXPECT_GT(c.freedom, kSamePoseDistance);
  EXPECT_EQ(c.competitor.kind, Competitor::Kind::slide);
  EXPECT_GE(c.competitor.distance, kSamePoseDistance);
  EXPECT_LT(std::abs(c.competitor.box.center().y() - r.matches.front().box.center().y()), 0.01);
  EXPECT_LT(c.local_margin, 3.0);  // the slid pose fits within the noise of the match
  EXPECT_LT(c.probability, kDefaultMinConfidence);
  // What a refusal at the default cut says (the match's own doubt line is kept for below a half).
  const std::string doubt = describe_doubt(c, r.matches.front().box);
  EXPECT_NE(doubt.find("along the box's x"), std::string::npos) << doubt;
}

TEST(MatchConfidence, AFlatPatchHasNoRivalOnItsOwnPlane) {
  // An empty patch of the table (the paper's empty spot), and a crate whose top is as flat and as
  // empty, 12 cm higher: a patch on the table has other patches of the table beside it, but its
  // only rival is the crate's top.
  TriangleMesh crate;
  crate.append(make_box_mesh({0.3, 0.3, 0.12}),
               pose_from_xyz_rpy({0.35, 0.15, kTable + 0.06}, {0, 0, 0}));
  const PointCloud scene = render_on_table(crate);
  const Box patch(pose_from_xyz_rpy({-0.3, -0.1, kTable + 0.04}, {0, 0, 0}), {0.2, 0.2, 0.1});
  CaptureSettings flat;
  flat.allow_flat = true;
  const Landmark landmark = capture(scene, patch, "patch", flat);
  ASSERT_TRUE(flat_normal(landmark.points, 0.005));
  EXPECT_FALSE(flat_normal(
      capture(render_scene({kCopies[1]}, false), box_at(kCopies[1]), "L").points, 0.005));
  const FindResult r = find_landmark(scene, landmark, FindSettings());
  ASSERT_GE(r.matches.size(), 2u);
  for (const Match& m : r.matches) {
    const MatchConfidence& c = m.confidence;
    SCOPED_TRACE(evidence(c));
    if (c.competitor.kind == Competitor::Kind::none) continue;
    // Any rival lies off the match's plane: the crate's top for a patch of the table, and back.
    EXPECT_GT(std::abs(c.competitor.box.center().z() - m.box.center().z()), 0.1);
  }
}

// The table with a post 30 cm tall standing at (x, y).
PointCloud table_with_post(double x, double y) {
  TriangleMesh post;
  post.append(make_box_mesh({0.06, 0.05, 0.3}),
              pose_from_xyz_rpy({x, y, kTable + 0.15}, {0, 0, 0}));
  return render_on_table(post);
}

TEST(MatchConfidence, APatchWhoseFreeSpaceIsHiddenIsNotConfirmed) {
  // A patch of the empty table, at its own place on the same table with a post just outside its
  // box: behind it (seen from the camera), the post hides nothing of it; in front of it, its
  // shadow hides part of the patch's free space, and of the table under it. Nothing the sensor
  // sees stands in the patch, yet nothing confirms that all of it is free: a robot must not put
  // something there.
  const Box patch(pose_from_xyz_rpy({-0.3, -0.1, kTable + 0.04}, {0, 0, 0}), {0.2, 0.2, 0.1});
  CaptureSettings flat;
  flat.allow_flat = true;
  const Landmark landmark = capture(render_on_table(TriangleMesh()), patch, "patch", flat);
  const LandmarkIndex prepared(landmark);
  const auto seen_at_capture_pose = [&](const PointCloud& scene) {
    return empty_space_seen_empty(SceneIndex(scene), landmark, prepared.empty_distances(),
                                  Eigen::Isometry3d::Identity());
  };
  EXPECT_GT(seen_at_capture_pose(table_with_post(-0.3, 0.045)), 0.99);
  const double hidden = seen_at_capture_pose(table_with_post(-0.3, -0.24));
  EXPECT_LT(hidden, 0.95);
  EXPECT_GT(hidden, 0.5);  // the shadow of a post, not a patch out of sight

  // The search measures it for every match of the patch; those beside the post that leave more of
  // their free space unseen than the empty-space allowance have no probability and say why.
  FindSettings every_match;
  every_match.selection.min_confidence = 0.0;
  const FindResult r = find_landmark(table_with_post(-0.3, -0.24), landmark, every_match);
  ASSERT_FALSE(r.matches.empty());
  std::size_t unconfirmed = 0;
  for (const Match& m : r.matches) {
    const MatchConfidence& c = m.confidence;
    SCOPED_TRACE(evidence(c));
    ASSERT_FALSE(std::isnan(c.free_space_seen));
    EXPECT_EQ(c.free_space_unconfirmed, c.free_space_seen < 0.99);
    if (!c.free_space_unconfirmed) continue;
    ++unconfirmed;
    EXPECT_EQ(c.probability, 0.0);
    EXPECT_NE(c.doubt.find("of the space its box says is free is seen free"), std::string::npos);
  }
  EXPECT_GE(unconfirmed, 1u);
  EXPECT_LT(unconfirmed, r.matches.size());  // the open table's patches are seen free

  // The rule, on its own: no probability, whatever the calibration says, and the doubt line.
  MatchConfidence c = r.matches.front().confidence;
  c.free_space_seen = 0.874;
  c.free_space_unconfirmed = true;
  calibrate(c, patch, &builtin_confidence_calibration());
  EXPECT_EQ(c.probability, 0.0);
  EXPECT_EQ(c.doubt,
            "only 87% of the space its box says is free is seen free (the rest is hidden or "
            "returned nothing)");

  // A landmark that is not flat has its own sides to hide its free space: it is not measured.
  const Landmark l = capture(render_scene({kCopies[1]}, false), box_at(kCopies[1]), "L");
  const FindResult shape = find_landmark(render_scene({kCopies[1]}, false), l, FindSettings());
  ASSERT_FALSE(shape.matches.empty());
  EXPECT_TRUE(std::isnan(shape.matches.front().confidence.free_space_seen));
}

}  // namespace
}  // namespace lmk
