// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/failure_pictures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "lmk/datasets/dataset.h"
#include "lmk/eval/detail/base64.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/depth_image.h"
#include "lmk/geometry/range_image.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/confidence/match_confidence.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

constexpr int kShrink = 4;  // the picture's pixels per side of one image pixel

// The frame's depth as a greyscale PNG, one pixel per kShrink x kShrink block (its first return),
// shaded from bright to dark between the frame's 2nd and 98th percentile depths.
std::string depth_png(const RangeImage& image) {
  const PinholeIntrinsics& k = image.intrinsics();
  std::vector<float> finite;
  for (float z : image.depths())
    if (!std::isnan(z)) finite.push_back(z);
  if (finite.empty()) finite.push_back(1.0f);
  const auto at = [&](double q) {
    auto it = finite.begin() + static_cast<std::ptrdiff_t>(q * (finite.size() - 1));
    std::nth_element(finite.begin(), it, finite.end());
    return static_cast<double>(*it);
  };
  const double near = at(0.02), far = std::max(at(0.98), near + 0.1);
  const int w = k.width / kShrink, h = k.height / kShrink;
  std::vector<std::uint8_t> grey(static_cast<std::size_t>(w) * h, 0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      for (int dv = 0; dv < kShrink; ++dv) {
        for (int du = 0; du < kShrink; ++du) {
          const float z = image.depths()[static_cast<std::size_t>(v * kShrink + dv) * k.width +
                                         u * kShrink + du];
          if (std::isnan(z)) continue;
          const double t = std::clamp((z - near) / (far - near), 0.0, 1.0);
          grey[static_cast<std::size_t>(v) * w + u] = static_cast<std::uint8_t>(235 - 185 * t);
          du = dv = kShrink;  // found one
        }
      }
    }
  }
  return greyscale_png(grey, w, h);
}

// The box's twelve edges as SVG lines in image pixels (edges with an end behind the sensor are
// left out).
std::string box_lines(const RangeImage& image, const Box& box, const char* colour, bool dashed) {
  const auto corners = box.corners();
  std::string out;
  for (int i = 0; i < 8; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const int j = i | (1 << axis);
      if (j == i) continue;
      const auto a = image.project(corners[i].cast<float>());
      const auto b = image.project(corners[j].cast<float>());
      if (!a || !b) continue;
      char line[256];
      std::snprintf(line, sizeof(line),
                    "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                    "stroke-width=\"3\"%s/>\n",
                    a->x(), a->y(), b->x(), b->y(), colour,
                    dashed ? " stroke-dasharray=\"8 6\"" : "");
      out += line;
    }
  }
  return out;
}

std::string percent(double fraction) {
  char text[16];
  std::snprintf(text, sizeof(text), "%.0f%%", 100.0 * fraction);
  return text;
}

}  // namespace

namespace {

// What the protocol made of a pair: which true instances a match found, and how many matches
// were false.
struct PairOutcome {
  PairInput in;
  std::vector<std::optional<std::size_t>> assigned;  ///< per match within the cut: its instance
  std::vector<char> found;                           ///< per true instance
  std::size_t missed = 0, false_found = 0;
};

PairOutcome outcome_of(const PairResult& p, const EvaluationSettings& settings) {
  PairOutcome o;
  o.in =
      matches_within(p, *settings.find.selection.threshold, settings.find.selection.min_confidence);
  o.assigned = assign_matches(o.in, settings.tolerance);
  o.found.assign(p.truth.size(), 0);
  for (const auto& a : o.assigned) {
    if (a) o.found[*a] = 1;
    o.false_found += a ? 0 : 1;
  }
  for (std::size_t t = 0; t < p.truth.size(); ++t) o.missed += !o.found[t] && !o.in.is_ignored(t);
  return o;
}

// The picture's boxes (the truth green, or grey where ignored; correct matches blue, false ones
// red) as SVG lines over `image`, and its caption naming each miss and false match.
void draw_pair(const PairResult& p, const PairOutcome& o, const RangeImage& image,
               const Eigen::Vector3d& box_size, const EvaluationSettings& settings,
               std::string& lines, std::string& caption) {
  const double threshold = *settings.find.selection.threshold;
  caption = p.scene + ", " + p.landmark + ": ";
  for (std::size_t t = 0; t < p.truth.size(); ++t) {
    lines += box_lines(image, Box(p.truth[t], box_size), "#228833", o.in.is_ignored(t));
    if (o.found[t] || o.in.is_ignored(t)) continue;
    char text[96];
    std::snprintf(text, sizeof(text), "missed instance %zu at %.2f m", t + 1,
                  (p.truth[t].translation() - p.sensor_position).norm());
    caption += text;
    if (t < p.truth_hidden.size()) caption += ", " + percent(p.truth_hidden[t]) + " hidden";
    caption += "; ";
  }
  // The matches matches_within() kept, in its order, which is the assignment's.
  std::size_t k_found = 0;
  for (const FoundBox& f : p.found) {
    if (!(f.error < threshold &&
          passes_confidence(f.confidence.probability, settings.find.selection.min_confidence))) {
      continue;
    }
    const bool correct = o.assigned[k_found++].has_value();
    lines += box_lines(image, f.box, correct ? "#4477aa" : "#ee6677", false);
    if (!correct) {
      char text[64];
      std::snprintf(text, sizeof(text), "false match at %.2f m, error ",
                    (f.box.center() - p.sensor_position).norm());
      caption += text + format_error(f.error, settings.find.selection.metric) + "; ";
    }
  }
  caption.resize(caption.size() - 2);
}

// The scene's depth image as a PNG, 480 pixels wide, with `lines` drawn over it.
std::string picture_svg(const RangeImage& image, const std::string& lines) {
  const PinholeIntrinsics& k = image.intrinsics();
  char head[256];
  std::snprintf(head, sizeof(head),
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"480\" height=\"%d\" "
                "viewBox=\"0 0 %d %d\">\n",
                480 * k.height / k.width, k.width, k.height);
  return std::string(head) + "<image width=\"" + std::to_string(k.width) + "\" height=\"" +
         std::to_string(k.height) +
         "\" preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\" "
         "href=\"data:image/png;base64," +
         detail::base64(depth_png(image)) + "\"/>\n" + lines + "</svg>";
}

}  // namespace

FailurePictures failure_pictures(const Evaluation& evaluation, const std::string& dataset_dir,
                                 std::size_t limit) {
  FailurePictures out;
  const Dataset dataset = load_dataset(dataset_dir);
  std::map<std::string, const DatasetScene*> scenes;
  for (const DatasetScene& s : dataset.scenes) scenes[s.name] = &s;
  std::map<std::string, Eigen::Vector3d> box_sizes;  // loaded on first need
  const auto box_size = [&](const std::string& name) {
    auto it = box_sizes.find(name);
    if (it != box_sizes.end()) return it->second;
    Eigen::Vector3d size = Eigen::Vector3d::Constant(0.1);
    for (const DatasetLandmark& l : dataset.landmarks)
      if (l.name == name) size = load_landmark((fs::path(dataset_dir) / l.file).string()).box.size;
    return box_sizes[name] = size;
  };

  for (const PairResult& p : evaluation.pairs) {
    const PairOutcome outcome = outcome_of(p, evaluation.settings);
    if (outcome.missed == 0 && outcome.false_found == 0) continue;
    ++out.pairs_with_failures;
    const auto scene = scenes.find(p.scene);
    if (out.pictures.size() >= limit || scene == scenes.end()) {
      ++out.unpictured;
      continue;
    }
    PointCloud cloud = read_cloud((fs::path(dataset_dir) / scene->second->file).string());
    cloud.T_cloud_sensor = scene->second->T_scene_sensor;
    const std::optional<RangeImage> image = RangeImage::from_cloud(cloud);
    if (!image || !image->organised()) {
      ++out.unpictured;
      continue;
    }
    FailurePicture picture;
    picture.scene = p.scene;
    picture.landmark = p.landmark;
    picture.missed = outcome.missed;
    picture.false_found = outcome.false_found;
    std::string lines;
    draw_pair(p, outcome, *image, box_size(p.landmark), evaluation.settings, lines,
              picture.caption);
    picture.svg = picture_svg(*image, lines);
    out.pictures.push_back(std::move(picture));
  }
  return out;
}

}  // namespace lmk
