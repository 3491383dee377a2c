#include "landmark/landmark.h"

#include <cmath>
#include <sstream>

#include "geometry/error.h"
#include "geometry/filters.h"
#include "geometry/pose.h"
#include "geometry/voxel_grid.h"

namespace lmk {
namespace {

std::string format_size(const Eigen::Vector3d& size) {
  std::ostringstream s;
  s << size.x() << " x " << size.y() << " x " << size.z() << " m";
  return s.str();
}

void check_settings(const CaptureSettings& s, const std::string& what) {
  if (!(s.leaf_size > 0.0) || !std::isfinite(s.leaf_size)) {
    throw Error(what + ": leaf size must be positive and finite");
  }
  if (!(s.max_box_side > 0.0) || !std::isfinite(s.max_box_side)) {
    throw Error(what + ": maximum box side must be positive and finite");
  }
}

void check_box(const Box& box, const CaptureSettings& s, const std::string& what) {
  if (!box.size.allFinite() || (box.size.array() <= 0.0).any()) {
    throw Error(what + ": box sides must be positive and finite, got " + format_size(box.size));
  }
  if (!is_valid_pose(box.pose)) {
    throw Error(what + ": box pose must be finite with a proper rotation");
  }
  if ((box.size.array() > s.max_box_side).any()) {
    throw Error(what + ": box of " + format_size(box.size) + " has a side over the " +
                std::to_string(s.max_box_side) + " m limit (raise max_box_side if intended)");
  }
}

}  // namespace

void Landmark::validate(const std::string& what) const {
  if (format_version != kLandmarkFormatVersion) {
    throw Error(what + ": landmark format version " + std::to_string(format_version) +
                " is not supported (this lmk reads version " +
                std::to_string(kLandmarkFormatVersion) + ")");
  }
  if (name.empty()) throw Error(what + ": landmark name is empty");
  check_settings(settings, what);
  check_box(box, settings, what);
  if (!sensor_origin.allFinite()) throw Error(what + ": sensor origin is not finite");
  if (points.empty()) throw Error(what + ": landmark has no points");
  if (points.count_finite() != points.size()) {
    throw Error(what + ": landmark points must all be finite");
  }
  points.validate(what);
}

Landmark capture(const PointCloud& scene, const Box& box, const std::string& name,
                 const CaptureSettings& settings) {
  const std::string what = "capture '" + name + "'";
  if (name.empty()) throw Error("capture: the landmark needs a name");
  check_settings(settings, what);
  check_box(box, settings, what);
  const PointCloud inside = crop(scene, box);
  if (inside.empty()) {
    const Eigen::Vector3d c = box.center();
    std::ostringstream s;
    s << what << ": no scene point inside the box centred at (" << c.x() << ", " << c.y() << ", "
      << c.z() << ") of " << format_size(box.size) << "; is it in the scene's frame?";
    throw Error(s.str());
  }
  Landmark landmark;
  landmark.name = name;
  landmark.points = voxel_downsample(inside, settings.leaf_size);
  if (landmark.points.size() < settings.min_points) {
    throw Error(what + ": only " + std::to_string(landmark.points.size()) +
                " points in the box after downsampling, fewer than the minimum of " +
                std::to_string(settings.min_points) + "; draw a larger box or lower min_points");
  }
  landmark.points.T_cloud_sensor = scene.T_cloud_sensor;
  landmark.box = box;
  landmark.sensor_origin = scene.sensor_origin();
  landmark.settings = settings;
  return landmark;
}

}  // namespace lmk
