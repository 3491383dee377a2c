// SPDX-License-Identifier: BSD-3-Clause
// lmk.Cloud: a point cloud built from numpy arrays or read from any file `lmk` reads, and seen as
// arrays again without a copy (docs/python.md, "Clouds").
#include <pybind11/stl.h>

#include <cmath>
#include <memory>

#include "bindings.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/pose.h"
#include "lmk/occupancy/tsdf_volume.h"

namespace lmk::python {
namespace {

// The shape of a cloud's arrays: (N, 3) unorganised, (H, W, 3) organised.
struct Layout {
  std::uint32_t width = 0, height = 1;
};

Layout layout_of(const py::buffer_info& info, const char* what) {
  const auto rows = [&](py::ssize_t i) { return static_cast<std::uint32_t>(info.shape[i]); };
  if (info.ndim == 2 && info.shape[1] == 3) return {rows(0), 1};
  if (info.ndim == 3 && info.shape[2] == 3) return {rows(1), rows(0)};
  throw py::value_error(std::string(what) +
                        ": must be an N x 3 array, or H x W x 3 for an organised cloud");
}

PointCloud cloud_from_arrays(const py::array& points, const py::object& colours,
                             const py::object& sensor_pose) {
  if (!py::isinstance<py::array_t<float>>(points) && !py::isinstance<py::array_t<double>>(points)) {
    throw py::value_error("points: must be an array of float32 or float64, not " +
                          std::string(py::str(points.dtype())));
  }
  const auto xyz = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(points);
  const py::buffer_info info = xyz.request();
  const Layout layout = layout_of(info, "points");
  PointCloud cloud;
  const std::size_t n = static_cast<std::size_t>(layout.width) * layout.height;
  const float* data = static_cast<const float*>(info.ptr);
  cloud.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points[i] = Eigen::Vector3f(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
  }
  cloud.width = layout.width;
  cloud.height = layout.height;
  if (!colours.is_none()) {
    if (!py::isinstance<py::array_t<std::uint8_t>>(colours)) {
      throw py::value_error("colours: must be an array of uint8 (r, g, b), one row per point");
    }
    const auto rgb = py::array_t<std::uint8_t, py::array::c_style>::ensure(colours);
    const py::buffer_info c = rgb.request();
    const Layout colour_layout = layout_of(c, "colours");
    if (colour_layout.width != layout.width || colour_layout.height != layout.height) {
      throw py::value_error("colours: must have the points' shape");
    }
    const auto* bytes = static_cast<const std::uint8_t*>(c.ptr);
    cloud.colors.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      cloud.colors[i] = Color{bytes[3 * i], bytes[3 * i + 1], bytes[3 * i + 2]};
    }
  }
  if (!sensor_pose.is_none()) cloud.T_cloud_sensor = pose_from_array(sensor_pose, "sensor_pose");
  return cloud;
}

// An array over `cloud`'s own memory, kept alive by `owner` (the Python Cloud): no copy.
template <typename T>
py::array view(const std::vector<T>& values, const PointCloud& cloud, std::size_t channels,
               const py::object& owner) {
  using Scalar = std::conditional_t<std::is_same_v<T, Color>, std::uint8_t, float>;
  const std::size_t stride = sizeof(T);
  std::vector<py::ssize_t> shape, strides;
  if (cloud.is_organized()) {
    shape = {cloud.height, cloud.width, static_cast<py::ssize_t>(channels)};
    strides = {static_cast<py::ssize_t>(stride * cloud.width), static_cast<py::ssize_t>(stride),
               sizeof(Scalar)};
  } else {
    shape = {static_cast<py::ssize_t>(values.size()), static_cast<py::ssize_t>(channels)};
    strides = {static_cast<py::ssize_t>(stride), sizeof(Scalar)};
  }
  py::array out(py::dtype::of<Scalar>(), shape, strides,
                reinterpret_cast<const Scalar*>(values.data()), owner);
  out.attr("setflags")(py::arg("write") = false);
  return out;
}

}  // namespace

void bind_clouds(py::module_& m) {
  py::class_<PointCloud, std::shared_ptr<PointCloud>>(
      m, "Cloud",
      "A point cloud: float xyz, N x 3, or H x W x 3 organised with NaN where the sensor had no "
      "return; optional uint8 colours of the same shape; the sensor's pose in the cloud's frame.")
      .def(py::init(&cloud_from_arrays), py::arg("points"), py::arg("colours") = py::none(),
           py::arg("sensor_pose") = py::none(),
           "Builds a cloud from arrays (copied): points float32 or float64, colours uint8, "
           "sensor_pose a 4x4 rigid transform (default: the identity).")
      .def_property_readonly(
          "points",
          [](const py::object& self) {
            const auto& c = self.cast<const PointCloud&>();
            return view(c.points, c, 3, self);
          },
          "The points as a read-only float32 array over the cloud's memory.")
      .def_property_readonly(
          "colours",
          [](const py::object& self) -> py::object {
            const auto& c = self.cast<const PointCloud&>();
            if (!c.has_colors()) return py::none();
            // Colour is r, g, b, a: the alpha byte is the fourth channel, left out by the shape.
            return view(c.colors, c, 3, self);
          },
          "The colours as a read-only uint8 array (r, g, b), or None.")
      .def_property_readonly("sensor_pose",
                             [](const PointCloud& c) { return pose_to_array(c.T_cloud_sensor); })
      .def_property_readonly("organised", &PointCloud::is_organized)
      .def_property_readonly("finite_points", &PointCloud::count_finite)
      .def("__len__", &PointCloud::size);
  m.def(
      "read_cloud", [](const std::string& path) { return read_cloud(path); }, py::arg("path"),
      "Reads a cloud file as `lmk` does (.pcd, .ply, .xyz).");
  m.def(
      "fuse",
      [](const std::vector<std::shared_ptr<PointCloud>>& clouds, const py::object& poses) {
        std::vector<DepthFrame> frames;
        for (std::size_t i = 0; i < clouds.size(); ++i) {
          if (!clouds[i])
            throw py::value_error("fuse: cloud " + std::to_string(i + 1) + " is None");
          frames.push_back({clouds[i].get()});
        }
        if (!poses.is_none()) {
          const py::list list = py::list(poses);
          if (list.size() != clouds.size()) {
            throw py::value_error("fuse: " + std::to_string(list.size()) + " poses for " +
                                  std::to_string(clouds.size()) + " clouds");
          }
          for (std::size_t i = 0; i < frames.size(); ++i) {
            frames[i].T_common_cloud =
                pose_from_array(list[i], "fuse: pose " + std::to_string(i + 1));
          }
        }
        const py::gil_scoped_release release;
        return fuse_frames(frames);
      },
      py::arg("clouds"), py::arg("poses") = py::none(),
      "Several organised frames of one scene as one, as `lmk find A.pcd B.pcd ...` fuses them "
      "(an OpenVDB truncated signed distance volume, rendered from the first frame's sensor): "
      "`poses`, when given, is each cloud's 4x4 pose in a common frame; without, the clouds are "
      "in one frame already. Search the result with lmk.find.");
}

Eigen::Isometry3d pose_from_array(const py::object& array, const std::string& what) {
  // Empty when `array` converts to no float64 array (ensure() clears Python's error then).
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw py::value_error(what + ": must be a 4 x 4 array");
  }
  Eigen::Matrix4d matrix;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) matrix(r, c) = a.at(r, c);
  if (!matrix.allFinite()) throw py::value_error(what + ": must be finite");
  Eigen::Isometry3d pose(matrix);
  if (!is_valid_pose(pose) || !matrix.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1))) {
    throw py::value_error(what + ": must be a rigid motion (a rotation and a translation)");
  }
  return pose;
}

py::array_t<double> pose_to_array(const Eigen::Isometry3d& pose) {
  py::array_t<double> out({4, 4});
  auto o = out.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) o(r, c) = pose.matrix()(r, c);
  return out;
}

Box box_from_arrays(const py::object& pose, const py::object& size, const std::string& what) {
  const auto s = py::array_t<double, py::array::forcecast>::ensure(size);
  if (!s || s.ndim() != 1 || s.shape(0) != 3) {
    throw py::value_error(what + ": size must be three side lengths");
  }
  const Box box(pose_from_array(pose, what + ": pose"), {s.at(0), s.at(1), s.at(2)});
  if (!box.is_valid()) throw py::value_error(what + ": sides must be positive and finite");
  return box;
}

py::dict box_to_dict(const Box& box) {
  py::dict d;
  d["pose"] = pose_to_array(box.pose);
  py::array_t<double> size(3);
  for (int i = 0; i < 3; ++i) size.mutable_at(i) = box.size[i];
  d["size"] = size;
  return d;
}

py::object json_to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace lmk::python
