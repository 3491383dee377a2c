// SPDX-License-Identifier: BSD-3-Clause
// The capture check (capture_check.h, issue #59) on scenes built here: two identical objects are
// each other's look-alike, a cylinder is symmetric about its axis, and what the check found is
// kept in the .lmk file, gained on load by a file written before it, and refused when forged.

#include "lmk/search/capture_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/detail/vdb_landmark_file.h"
#include "lmk/landmark/internal/capture_findings_json.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/sim/mesh.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using namespace test_scenes;
using test::error_of;
using test::ScratchDir;

TEST(CaptureCheck, FindsTheLookAlikeBesideTheLandmark) {
  const PointCloud scene = render_scene({kCopies[0], kCopies[1]}, false);
  const Landmark landmark = capture(scene, box_at(kCopies[0]), "L");
  const CaptureCheck check = check_capture(landmark, &scene);
  const CaptureFindings& f = check.findings;
  EXPECT_TRUE(f.present);
  ASSERT_TRUE(f.look_alike_checked);
  EXPECT_TRUE(f.found_itself);
  EXPECT_EQ(f.look_alikes, 1u);
  // The copy, seen from another angle, scores no better than the captured instance itself.
  EXPECT_GE(f.look_alike_ratio, 1.0);
  EXPECT_TRUE(std::isfinite(f.look_alike_ratio));
  EXPECT_TRUE(f.warned());
  ASSERT_FALSE(f.warnings().empty());
  EXPECT_NE(f.warnings().back().find("1 other place"), std::string::npos);
  // The L's corners fix it: no slide, no symmetry.
  EXPECT_EQ(f.slide, 0.0);
  EXPECT_TRUE(f.symmetry_axes.empty());

  // Alone on its table, it warns of nothing; without the scene, the look-alikes are unknown.
  const PointCloud alone = render_scene({kCopies[0]}, false);
  const Landmark distinct = capture(alone, box_at(kCopies[0]), "L");
  EXPECT_FALSE(check_capture(distinct, &alone).findings.warned());
  const CaptureFindings unchecked = check_capture(distinct, nullptr).findings;
  EXPECT_FALSE(unchecked.look_alike_checked);
  EXPECT_TRUE(std::isnan(unchecked.noise));
}

// A cylinder standing on the table turns freely about its vertical axis: a symmetry, not a
// warning.
TEST(CaptureCheck, ACylinderIsSymmetricAboutItsAxis) {
  TriangleMesh world;
  world.append(make_cylinder_mesh(0.04, 0.2, 48),
               pose_from_xyz_rpy({0, 0, kTable + 0.1}, {0, 0, 0}));
  const PointCloud scene = render_on_table(world);
  const Box box(pose_from_xyz_rpy({0, 0, kTable + 0.11}, {0, 0, 0}), {0.14, 0.14, 0.26});
  const Landmark landmark = capture(scene, box, "can");
  const CaptureCheck check = check_capture(landmark, &scene);
  const CaptureFindings& f = check.findings;
  std::string motions;
  for (const Slide& s : check.slides.slides)
    motions += (s.turn ? " turn " : " slide ") + std::to_string(s.extent);
  ASSERT_EQ(f.symmetry_axes.size(), 1u) << "motions:" << motions;
  EXPECT_NEAR(std::abs(f.symmetry_axes[0].z()), 1.0, 0.05);
  // Its axis passes through the cylinder's (0, 0), within a centimetre.
  EXPECT_LT(f.symmetry_centre.head<2>().norm(), 0.01);
}

// The capture's axis becomes the evaluation's symmetry in the box frame, through the cylinder's
// axis even where the box is not centred on it: a turn about that axis keeps the cylinder in place
// but moves the box's centre.
TEST(CaptureCheck, TheCapturedAxisIsASymmetryInTheBoxFrame) {
  TriangleMesh world;
  world.append(make_cylinder_mesh(0.04, 0.2, 48),
               pose_from_xyz_rpy({0, 0, kTable + 0.1}, {0, 0, 0}));
  const PointCloud scene = render_on_table(world);
  const double yaw = 0.5;  // the box turned about z, and its centre 3 cm off the axis
  const Box box(pose_from_xyz_rpy({0.03, 0, kTable + 0.11}, {0, 0, yaw}), {0.2, 0.2, 0.26});
  Landmark landmark = capture(scene, box, "can");
  landmark.findings = check_capture(landmark, &scene).findings;
  const std::optional<Symmetry> symmetry = capture_symmetry(landmark);
  ASSERT_TRUE(symmetry.has_value());
  ASSERT_TRUE(symmetry->axis.has_value());
  EXPECT_EQ(symmetry->order, 0);
  EXPECT_NEAR(std::abs(symmetry->axis->z()), 1.0, 0.05);
  // The axis's point, back in the capture frame, lies on the cylinder's axis within a centimetre.
  const Eigen::Vector3d through = box.pose * symmetry->centre;
  EXPECT_LT(through.head<2>().norm(), 0.01);
  // A landmark without findings (built by hand) has no captured symmetry.
  landmark.findings = CaptureFindings();
  EXPECT_FALSE(capture_symmetry(landmark).has_value());
}

TEST(CaptureCheck, FindingsTravelInTheFileAndAnOldFileGainsThem) {
  const ScratchDir dir;
  const PointCloud scene = render_scene({kCopies[0], kCopies[1]}, false);
  Landmark landmark = capture(scene, box_at(kCopies[0]), "L");

  // A file written before the findings existed (version 2). Loading it measures what needs no
  // capture scene.
  const std::string old_file = (dir.path() / "old.lmk").string();
  detail::write_vdb_landmark(old_file, landmark);
  EXPECT_EQ(landmark_file_version(old_file), 2);
  const Landmark upgraded = load_landmark(old_file);
  const CaptureFindings expected = check_capture(landmark, nullptr).findings;
  EXPECT_TRUE(upgraded.findings.present);
  EXPECT_FALSE(upgraded.findings.look_alike_checked);
  EXPECT_EQ(upgraded.findings.slide, expected.slide);
  EXPECT_EQ(upgraded.findings.symmetry_axes.size(), expected.symmetry_axes.size());

  // With them, read back as written.
  landmark.findings = check_capture(landmark, &scene).findings;
  const std::string file = (dir.path() / "new.lmk").string();
  save_landmark(file, landmark);
  EXPECT_EQ(landmark_file_version(file), kLandmarkFormatVersion);
  const CaptureFindings read = load_landmark(file).findings;
  EXPECT_EQ(read.look_alikes, 1u);
  EXPECT_TRUE(read.look_alike_checked);
  EXPECT_DOUBLE_EQ(read.look_alike_ratio, landmark.findings.look_alike_ratio);
  EXPECT_EQ(std::isnan(read.noise), std::isnan(landmark.findings.noise));
  if (!std::isnan(read.noise)) {
    EXPECT_DOUBLE_EQ(read.noise, landmark.findings.noise);
  }
  EXPECT_TRUE(read.warned());
}

// A forged file's findings cannot reach a search: each field is checked on reading.
TEST(CaptureCheck, ForgedFindingsAreRefused) {
  CaptureFindings f;
  f.present = true;
  f.noise = 0.002;
  f.symmetry_axes = {Eigen::Vector3d::UnitZ()};
  const nlohmann::json good = detail::capture_findings_to_json(f);
  EXPECT_NO_THROW(detail::capture_findings_from_json(good, "f"));
  const auto refused = [&](const char* key, const nlohmann::json& value) {
    nlohmann::json bad = good;
    bad[key] = value;
    return !error_of([&] { detail::capture_findings_from_json(bad, "f"); }).empty();
  };
  EXPECT_TRUE(refused("noise", -1.0));
  EXPECT_TRUE(refused("noise", "2 mm"));
  EXPECT_TRUE(refused("slide_axis", nlohmann::json::array({2.0, 0.0, 0.0})));
  EXPECT_TRUE(refused(
      "symmetry_axes",
      nlohmann::json::array({nlohmann::json::array({0, 0, 1}), nlohmann::json::array({0, 0, 1}),
                             nlohmann::json::array({0, 0, 1}), nlohmann::json::array({0, 0, 1})})));
  EXPECT_TRUE(refused("look_alikes", -3));
  EXPECT_TRUE(refused("found_itself", 1));
  EXPECT_TRUE(refused("look_alike_ratio", nlohmann::json::array()));
  nlohmann::json missing = good;
  missing.erase("slide_turn");
  EXPECT_FALSE(error_of([&] { detail::capture_findings_from_json(missing, "f"); }).empty());
  EXPECT_FALSE(error_of([&] { detail::capture_findings_from_json("[]", "f"); }).empty());
}

}  // namespace
}  // namespace lmk
