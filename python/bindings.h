// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the parts of the `lmk` Python module share: their registration functions, and the
// conversions between numpy arrays and lmk's types, each refusing a wrong dtype, shape or a
// non-finite pose with a ValueError that names it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "lmk/geometry/box.h"
#include "lmk/search/find_settings.h"

namespace lmk::python {

namespace py = pybind11;

void bind_clouds(py::module_& m);
void bind_landmarks(py::module_& m);
void bind_search(py::module_& m);
void bind_tracking(py::module_& m);
void bind_evaluation(py::module_& m);
/// With lmk.Error, the base of lmk.Refused.
void bind_robot(py::module_& m, const py::object& error);

/// A keyword's value as the command line writes it: booleans as true/false, sequences as
/// space-separated values, numbers in Python's own shortest form.
std::string setting_text(const py::handle& value);
/// A keyword's name as a flag's key: max_tilt -> max-tilt.
std::string setting_key(std::string name);
/// Calls set(name, key, text) for each keyword: its Python name, its name as a flag's key and its
/// value as the command line writes it. An lmk::Error from `set` becomes a ValueError with its
/// message: what lmk.find's and lmk.capture's settings keywords share.
void set_from_keywords(const py::kwargs& keywords,
                       const std::function<void(const std::string& name, const std::string& key,
                                                const std::string& text)>& set);
/// Search settings from keywords named as `lmk find`'s flags (max_tilt for --max-tilt), set and
/// checked by the settings' descriptions; ValueError with the CLI's message for a bad one.
FindSettings settings_from_keywords(const py::kwargs& keywords);

/// A 4x4 rigid transform from an array; ValueError naming `what` for another shape, a non-finite
/// value or a matrix that is no rigid motion.
Eigen::Isometry3d pose_from_array(const py::object& array, const std::string& what);
/// A 4x4 float64 array of `pose`.
py::array_t<double> pose_to_array(const Eigen::Isometry3d& pose);
/// A box from its 4x4 pose and its three sides (m); ValueError for a bad one.
Box box_from_arrays(const py::object& pose, const py::object& size, const std::string& what);
/// {"pose": 4x4 array, "size": 3 array}
py::dict box_to_dict(const Box& box);
/// A JSON value as plain Python (dict, list, float, ...), through Python's own json module.
py::object json_to_python(const nlohmann::json& j);

}  // namespace lmk::python
