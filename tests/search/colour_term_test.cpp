// SPDX-License-Identifier: BSD-3-Clause
// Colour (issue #35): chroma ignores a uniform change of brightness and tells red from blue; the
// colour term turns down a look-alike of the wrong colour; a landmark keeps its colour in its file;
// a search without colour gives the answers it gave before colour existed.

#include "lmk/search/metrics/colour_term.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "lmk/geometry/chroma.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/find_landmark.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using namespace test_scenes;

const Color kRed{200, 40, 30};
const Color kBlue{30, 50, 190};
const Color kGrey{128, 128, 128};

Color scaled(const Color& c, double gain) {
  const auto channel = [gain](std::uint8_t v) {
    return static_cast<std::uint8_t>(std::min(255.0, std::round(v * gain)));
  };
  return {channel(c.r), channel(c.g), channel(c.b)};
}

// The tests' tabletop with each copy of the L-shape painted: the first copy (the one captured) and
// the third red, the second blue, everything else grey.
PointCloud painted_scene(double gain = 1.0) {
  PointCloud scene = render_scene(kCopies, true);
  const std::vector<Color> paint = {kRed, kBlue, kRed};
  scene.colors.assign(scene.size(), scaled(kGrey, gain));
  for (std::size_t i = 0; i < scene.size(); ++i) {
    for (std::size_t c = 0; c < kCopies.size(); ++c) {
      if (box_at(kCopies[c]).contains(scene.points[i]) && scene.points[i].z() > kTable + 0.004) {
        scene.colors[i] = scaled(paint[c], gain);
      }
    }
  }
  return scene;
}

FindSettings with_colour(double weight) {
  FindSettings s;
  s.selection.colour_weight = weight;
  return s;
}

// The copy a match lies on, or -1.
int copy_of(const Match& m) {
  for (std::size_t c = 0; c < kCopies.size(); ++c) {
    if ((m.box.center() - box_at(kCopies[c]).center()).norm() < 0.01) return static_cast<int>(c);
  }
  return -1;
}

std::vector<int> copies_found(const FindResult& r) {
  std::vector<int> copies;
  for (const Match& m : r.matches) copies.push_back(copy_of(m));
  std::sort(copies.begin(), copies.end());
  return copies;
}

TEST(Chroma, IgnoresAUniformChangeOfBrightnessAndTellsRedFromBlue) {
  for (const Color& c : {kRed, kBlue, kGrey}) {
    for (double gain : {0.5, 0.8, 1.2}) {
      const auto a = chroma_of(c), b = chroma_of(scaled(c, gain));
      ASSERT_TRUE(a && b);
      EXPECT_LT(chroma_distance(*a, *b), 0.01) << gain;  // 8-bit rounding only
    }
  }
  EXPECT_GT(chroma_distance(*chroma_of(kRed), *chroma_of(kBlue)), 0.8);
  EXPECT_GT(chroma_distance(*chroma_of(kRed), *chroma_of(kGrey)), 0.4);
  EXPECT_FALSE(chroma_of({10, 20, 15}));     // too dark for a hue
  EXPECT_FALSE(chroma_of({255, 255, 255}));  // clipped
}

// The painted tabletop and the landmark cut from its first (red) copy, built once for the tests.
struct RedL {
  PointCloud scene = painted_scene();
  Landmark landmark = capture(scene, box_at(kCopies[0]), "red L");
};
const RedL& red_l() {
  static const RedL fixture;
  return fixture;
}

TEST(ColourTerm, ACaptureKeepsTheColourOfItsPoints) {
  ASSERT_TRUE(red_l().landmark.points.has_colors());
  std::size_t red = 0;
  for (const Color& c : red_l().landmark.points.colors) red += c == kRed;
  EXPECT_GT(red, red_l().landmark.points.size() / 2);
}

TEST(ColourTerm, TurnsDownTheLookAlikeOfTheWrongColour) {
  const FindResult shape_only = find_landmark(red_l().scene, red_l().landmark, with_colour(0.0));
  EXPECT_EQ(copies_found(shape_only), (std::vector<int>{0, 1, 2}));
  for (const Match& m : shape_only.matches) EXPECT_FALSE(m.terms.colour);

  FindSettings s = with_colour(1.0);
  s.execution.keep_suppressed = true;
  const FindResult coloured = find_landmark(red_l().scene, red_l().landmark, s);
  EXPECT_EQ(copies_found(coloured), (std::vector<int>{0, 2}));
  for (const Match& m : coloured.matches) {
    ASSERT_TRUE(m.terms.colour);
    EXPECT_GT(m.terms.colour->points, 100u);
    EXPECT_LT(m.terms.colour->difference, 0.05);
    EXPECT_EQ(m.terms.colour->penalty, 0.0);
  }
  EXPECT_EQ(coloured.stats.rejected[RejectionReason::colour_differs], 1u);
  const auto blue = std::find_if(coloured.rejected.begin(), coloured.rejected.end(),
                                 [](const Rejection& r) { return copy_of(r.candidate) == 1; });
  ASSERT_NE(blue, coloured.rejected.end());
  EXPECT_EQ(blue->reason, RejectionReason::colour_differs);
  ASSERT_TRUE(blue->candidate.terms.colour);
  EXPECT_GT(blue->candidate.terms.colour->difference, 0.5);
  EXPECT_NE(describe_rejections(coloured.stats).find("1 colour differs"), std::string::npos);
}

TEST(ColourTerm, IgnoresAUniformChangeOfBrightness) {
  const FindSettings s = with_colour(1.0);
  const FindResult bright = find_landmark(red_l().scene, red_l().landmark, s);
  const FindResult dim = find_landmark(painted_scene(0.5), red_l().landmark, s);
  ASSERT_EQ(copies_found(dim), copies_found(bright));
  for (std::size_t i = 0; i < dim.matches.size(); ++i) {
    ASSERT_TRUE(dim.matches[i].terms.colour && bright.matches[i].terms.colour);
    EXPECT_NEAR(dim.matches[i].terms.colour->difference, bright.matches[i].terms.colour->difference,
                0.01);
    EXPECT_NEAR(dim.matches[i].error, bright.matches[i].error, 1e-4);
  }
}

TEST(ColourTerm, ASceneWithoutColourGivesTheShapeOnlyAnswers) {
  PointCloud grey = red_l().scene;
  grey.colors.clear();
  const FindResult with = find_landmark(grey, red_l().landmark, with_colour(1.0));
  const FindResult without = find_landmark(grey, red_l().landmark, with_colour(0.0));
  ASSERT_EQ(with.matches.size(), without.matches.size());
  for (std::size_t i = 0; i < with.matches.size(); ++i) {
    EXPECT_EQ(with.matches[i].error, without.matches[i].error);
    EXPECT_TRUE(with.matches[i].T_scene_capture.isApprox(without.matches[i].T_scene_capture, 0.0));
  }
}

TEST(ColourTerm, TheLandmarkFileKeepsItsColour) {
  const test::ScratchDir dir;
  const std::string coloured = dir.file("red.lmk"), plain = dir.file("plain.lmk");
  save_landmark(coloured, red_l().landmark);
  Landmark uncoloured = red_l().landmark;
  uncoloured.points.colors.clear();
  save_landmark(plain, uncoloured);
  EXPECT_EQ(landmark_file_version(coloured), kLandmarkFormatVersion);
  const Landmark back = load_landmark(coloured);
  EXPECT_EQ(back.points.colors, red_l().landmark.points.colors);
  EXPECT_EQ(back.points.points, red_l().landmark.points.points);
  EXPECT_FALSE(back.multi_view());
  EXPECT_FALSE(load_landmark(plain).points.has_colors());
}

}  // namespace
}  // namespace lmk
