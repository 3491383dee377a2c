// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/cloud_download.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "lmk/geometry/point_cloud.h"

namespace lmk::serve {
namespace {

// Millimetres are finer than any depth camera resolves and keep the JSON small.
long to_mm(float v) { return std::lround(static_cast<double>(v) * 1000.0); }

}  // namespace

CloudDownload::CloudDownload(Scene scene, std::size_t max_points) : scene_(std::move(scene)) {
  const std::size_t finite = scene_.cloud->count_finite();
  stride_ = std::max<std::size_t>(1, (finite + max_points - 1) / max_points);
  kept_ = (finite + stride_ - 1) / stride_;
}

void CloudDownload::write_points(std::string& out, std::size_t count, bool positions) {
  const PointCloud& c = *scene_.cloud;
  for (std::size_t n = 0; n < count && cursor_ < c.size(); ++cursor_) {
    if (!is_finite(c.points[cursor_])) continue;
    if (seen_++ % stride_ != 0) continue;
    const long values[3] = {positions ? to_mm(c.points[cursor_].x()) : long{c.colors[cursor_].r},
                            positions ? to_mm(c.points[cursor_].y()) : long{c.colors[cursor_].g},
                            positions ? to_mm(c.points[cursor_].z()) : long{c.colors[cursor_].b}};
    for (long v : values) {
      if (written_++ > 0) out += ',';
      out += std::to_string(v);
    }
    ++n;
  }
}

std::string CloudDownload::next(std::size_t points_per_piece) {
  std::string out;
  const bool colours = scene_.cloud->has_colors();
  const auto start_points = [this] { cursor_ = seen_ = written_ = 0; };
  switch (part_) {
    case Part::head:
      out = "{\"id\":" + nlohmann::json(scene_.id).dump() + ",\"points\":" + std::to_string(kept_) +
            ",\"stride\":" + std::to_string(stride_) + ",\"unit\":\"mm\",\"positions\":[";
      start_points();
      part_ = Part::positions;
      break;
    case Part::positions:
      write_points(out, points_per_piece, true);
      if (cursor_ >= scene_.cloud->size()) part_ = Part::between;
      break;
    case Part::between:
      out = colours ? "],\"colors\":[" : "],\"colors\":null}";
      start_points();
      part_ = colours ? Part::colors : Part::done;
      break;
    case Part::colors:
      write_points(out, points_per_piece, false);
      if (cursor_ >= scene_.cloud->size()) part_ = Part::tail;
      break;
    case Part::tail:
      out = "]}";
      part_ = Part::done;
      break;
    case Part::done:
      break;
  }
  // A piece may be empty before the end (a stretch of no finite points): go on to the next.
  if (out.empty() && part_ != Part::done) return next(points_per_piece);
  return out;
}

}  // namespace lmk::serve
