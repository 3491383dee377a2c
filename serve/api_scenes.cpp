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

}  // namespace

ApiResponse Api::scenes() const {
  nlohmann::json list = nlohmann::json::array();
  for (const Scene& s : scenes_.list()) list.push_back(scene_summary(s));
  return {200, {{"scenes", list}}};
}

ApiResponse Api::upload_scene(const std::string& name, const std::string& bytes) {
  return {201, scene_summary(scenes_.add_upload(name, bytes))};
}

ApiResponse Api::upload_scene(UploadFile& file) {
  return {201, scene_summary(scenes_.add_upload(file))};
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

// The most points a cloud download sends: a 1080p frame's 2 million. The answer is streamed, but
// the page draws it whole, and 5 million points took 11 s (issue #34, finding 3).
constexpr long long kMaxCloudDownloadPoints = 2'000'000;

CloudDownload Api::scene_cloud(const std::string& id, const std::string& max_points_text) const {
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
  return CloudDownload(scenes_.get(id), max_points);
}

}  // namespace lmk::serve
