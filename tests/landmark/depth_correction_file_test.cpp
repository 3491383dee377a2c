// SPDX-License-Identifier: BSD-3-Clause
// A depth correction (geometry/depth_correction.h) moves each point along its sensor's ray by its
// pixel's cell's D, in whatever frame the cloud is expressed; its file round-trips and a bad one is
// refused naming the file and the field.

#include "lmk/landmark/depth_correction_file.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using test::error_of;
using test::ScratchDir;
using test::write_text;

// Two cells side by side over a 4 x 3 image: the left reads 1% per metre too near, the right 2%
// too far.
DepthCorrection two_cells() {
  DepthCorrection c;
  c.width = 4;
  c.height = 3;
  c.cols = 2;
  c.rows = 1;
  c.per_metre = {0.01, -0.02};
  return c;
}

// A 4 x 3 organised frame in its camera's optical frame, a point per pixel at depth 1-2 m, one
// hole.
PointCloud camera_frame() {
  PointCloud f;
  f.width = 4;
  f.height = 3;
  for (int v = 0; v < 3; ++v) {
    for (int u = 0; u < 4; ++u) {
      const float z = 1.0f + 0.1f * static_cast<float>(u + 4 * v);
      f.points.emplace_back((u - 1.5f) * z / 500.0f, (v - 1.0f) * z / 500.0f, z);
    }
  }
  f.points[5] = Eigen::Vector3f::Constant(std::nanf(""));
  return f;
}

TEST(DepthCorrection, MovesEachPointAlongItsRayByItsCellsError) {
  const DepthCorrection c = two_cells();
  const PointCloud raw = camera_frame();
  PointCloud corrected = raw;
  c.apply(corrected);
  for (int v = 0; v < 3; ++v) {
    for (int u = 0; u < 4; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * 4 + u;
      if (!is_finite(raw.points[i])) {
        EXPECT_FALSE(is_finite(corrected.points[i]));
        continue;
      }
      const double z = raw.points[i].z(), d = u < 2 ? 0.01 : -0.02;
      EXPECT_NEAR(corrected.points[i].z(), z + d * z * z, 1e-5) << u << ", " << v;
      // Along the ray: the direction from the sensor does not change.
      EXPECT_NEAR(corrected.points[i].normalized().dot(raw.points[i].normalized()), 1.0, 1e-6);
    }
  }
}

TEST(DepthCorrection, WorksInTheSensorsFrameWhateverFrameTheCloudIsIn) {
  const DepthCorrection c = two_cells();
  PointCloud in_camera = camera_frame();
  const Eigen::Isometry3d T_base_camera = pose_from_xyz_rpy({0.2, -0.1, 1.3}, {-1.7, 0.1, 0.6});
  PointCloud in_base = in_camera.transformed(T_base_camera);
  ASSERT_TRUE(in_base.T_cloud_sensor.isApprox(T_base_camera));
  c.apply(in_camera);
  c.apply(in_base);
  for (std::size_t i = 0; i < in_camera.size(); ++i) {
    if (!is_finite(in_camera.points[i])) continue;
    EXPECT_LT((T_base_camera.cast<float>() * in_camera.points[i] - in_base.points[i]).norm(), 1e-5)
        << i;
  }
}

TEST(DepthCorrection, RefusesAFrameItWasNotFittedOn) {
  const DepthCorrection c = two_cells();
  PointCloud other = camera_frame();
  other.width = 6;
  other.height = 2;
  EXPECT_NE(
      error_of([&] { c.apply(other); }).find("fitted on 4 x 3 images, given a frame of 6 x 2"),
      std::string::npos);
  PointCloud unorganised = camera_frame();
  unorganised.set_unorganized();
  EXPECT_NE(error_of([&] { c.apply(unorganised); }).find("an unorganised cloud"),
            std::string::npos);
}

TEST(DepthCorrectionFile, RoundTripsWhatTheFitSaw) {
  const ScratchDir dir;
  DepthCalibration fit;
  fit.correction = two_cells();
  fit.correspondences = 1234;
  fit.rms_before = 0.016;
  fit.rms_after = 0.013;
  fit.source = "a sequence";
  save_depth_correction(dir.file("c.json"), fit);
  const DepthCalibration back = load_depth_correction(dir.file("c.json"));
  EXPECT_EQ(back.correction.per_metre, fit.correction.per_metre);
  EXPECT_EQ(back.correction.width, 4);
  EXPECT_EQ(back.correction.height, 3);
  EXPECT_EQ(back.correction.cols, 2);
  EXPECT_EQ(back.correction.rows, 1);
  EXPECT_EQ(back.correspondences, 1234u);
  EXPECT_DOUBLE_EQ(back.rms_after, 0.013);
  EXPECT_EQ(back.source, "a sequence");

  PointCloud frame = camera_frame(), expected = camera_frame();
  correct_depth(frame, dir.file("c.json"));
  fit.correction.apply(expected);
  EXPECT_EQ(frame.points[0], expected.points[0]);
  PointCloud untouched = camera_frame();
  correct_depth(untouched, "");  // no file: nothing to undo
  EXPECT_EQ(untouched.points[0], camera_frame().points[0]);
}

TEST(DepthCorrectionFile, ABadFileIsRefusedNamingTheFileAndTheField) {
  const ScratchDir dir;
  const std::string head = R"({"format": "lmk-depth-correction", "version": 1, )";
  const auto refusal = [&](const std::string& text) {
    write_text(dir.file("bad.json"), text);
    return error_of([&] { load_depth_correction(dir.file("bad.json")); });
  };
  const std::string file = dir.file("bad.json");
  EXPECT_NE(refusal("{").find(file + ": not valid JSON"), std::string::npos);
  EXPECT_NE(
      refusal(R"({"format": "lmk-program", "version": 1})").find("format: is \"lmk-program\""),
      std::string::npos);
  EXPECT_NE(refusal(R"({"format": "lmk-depth-correction", "version": 2})")
                .find("depth correction format version 2 is not supported"),
            std::string::npos);
  EXPECT_NE(refusal(head + R"("image": [640], "cells": [1, 1], "per_metre": [0]})")
                .find("image: must be two whole numbers"),
            std::string::npos);
  EXPECT_NE(refusal(head + R"("image": [4, 3], "cells": [3, 1], "per_metre": [0, 0]})")
                .find("2 values for 3 cells"),
            std::string::npos);
  EXPECT_NE(refusal(head + R"("image": [4, 3], "cells": [1, 1], "per_metre": ["x"]})")
                .find("per_metre[0]: must be a number"),
            std::string::npos);
  EXPECT_NE(
      refusal(head + R"("image": [4, 3], "cells": [1, 1], "per_metre": [0.5]})").find("cell 0's D"),
      std::string::npos);
  EXPECT_NE(refusal(head + R"("image": [4, 3], "cells": [5, 1], "per_metre": [0, 0, 0, 0, 0]})")
                .find("do not divide a 4 x 3 image"),
            std::string::npos);
}

}  // namespace
}  // namespace lmk
