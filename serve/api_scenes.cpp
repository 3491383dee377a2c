// SPDX-License-Identifier: BSD-3-Clause
// The scene endpoints: the picker's list, uploads, a scene's facts and its points for the view.
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/landmark.h"
#include "lmk/serve/api.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {
namespace {

nlohmann::json scene_summary(const Scene& s) {
  return {{"id", s.id},
          {"name", s.name},
          {"source", s.source},
          {"points", s.cloud->size()},
          {"has_rgb", s.cloud->has_colors()}};
}

// Millimetres are finer than any depth camera resolves and keep the JSON small.
long to_mm(float v) { return std::lround(static_cast<double>(v) * 1000.0); }

}  // namespace

ApiResponse Api::scenes() const {
  nlohmann::json list = nlohmann::json::array();
  for (const Scene& s : scenes_.list()) list.push_back(scene_summary(s));
  return {200, {{"scenes", list}}};
}

ApiResponse Api::upload_scene(const std::string& name, const std::string& bytes) {
  if (name.empty()) {
    throw bad_request("upload: give the file name as ?name=FILE.pcd (its extension is the format)");
  }
  return {201, scene_summary(scenes_.add_upload(name, bytes))};
}

ApiResponse Api::scene(const std::string& id) const {
  const Scene s = scenes_.get(id);
  const PointCloud& c = *s.cloud;
  nlohmann::json j = scene_summary(s);
  j["finite_points"] = c.count_finite();
  j["organised"] = c.is_organized();
  j["width"] = c.width;
  j["height"] = c.height;
  const Eigen::AlignedBox3f b = c.bounds();
  j["bounds"] = {{"min", detail::vector_to_json(b.min().cast<double>())},
                 {"max", detail::vector_to_json(b.max().cast<double>())}};
  j["sensor"] = detail::pose_to_json(c.T_cloud_sensor);
  const FindSettings find = scene_find_settings();
  j["base_frame"] = find.scene.base_frame;
  j["up"] = detail::vector_to_json(
      find.scene.up.value_or(default_up(c.T_cloud_sensor, find.scene.base_frame)).normalized());
  return {200, j};
}

// The most points a cloud download sends: a 1080p frame's 2 million. The answer is JSON built in
// memory; 5 million points took 1.08 GB and 11 s (issue #34, finding 3).
constexpr long long kMaxCloudDownloadPoints = 2'000'000;

ApiResponse Api::scene_cloud(const std::string& id, const std::string& max_points_text) const {
  std::size_t max_points = 400000;
  if (!max_points_text.empty()) {
    try {
      std::size_t used = 0;
      const long long n = std::stoll(max_points_text, &used);
      if (used != max_points_text.size() || n < 1 || n > kMaxCloudDownloadPoints) {
        throw bad_request("");
      }
      max_points = static_cast<std::size_t>(n);
    } catch (const std::exception&) {
      throw bad_request("cloud: max_points=" + printable(max_points_text) +
                        ": must be a whole number in [1, " +
                        std::to_string(kMaxCloudDownloadPoints) + "]");
    }
  }
  const Scene s = scenes_.get(id);
  const PointCloud& c = *s.cloud;
  const std::size_t finite = c.count_finite();
  // Every k-th finite point, k the smallest that keeps within max_points.
  const std::size_t stride = std::max<std::size_t>(1, (finite + max_points - 1) / max_points);
  nlohmann::json positions = nlohmann::json::array(), colors = nlohmann::json::array();
  std::size_t kept = 0, seen = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Eigen::Vector3f& p = c.points[i];
    if (!is_finite(p)) continue;
    if (seen++ % stride != 0) continue;
    positions.push_back(to_mm(p.x()));
    positions.push_back(to_mm(p.y()));
    positions.push_back(to_mm(p.z()));
    if (c.has_colors()) {
      colors.push_back(c.colors[i].r);
      colors.push_back(c.colors[i].g);
      colors.push_back(c.colors[i].b);
    }
    ++kept;
  }
  nlohmann::json j = {
      {"id", s.id}, {"points", kept}, {"stride", stride}, {"unit", "mm"}, {"positions", positions}};
  j["colors"] = c.has_colors() ? colors : nlohmann::json(nullptr);
  return {200, j};
}

}  // namespace lmk::serve
