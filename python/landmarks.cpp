// SPDX-License-Identifier: BSD-3-Clause
// lmk.Landmark, lmk.load_landmark and lmk.capture: a landmark cut out of a cloud with a box, with
// the verdict of the distinctiveness check and the slide check, as `lmk capture` gives them
// (docs/python.md, "Landmarks").
#include <pybind11/stl.h>

#include <memory>

#include "bindings.h"
#include "lmk/landmark/internal/capture_findings_json.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/landmark/slide_check.h"
#include "lmk/search/capture_check.h"
#include "lmk/search/internal/find_result_json.h"

namespace lmk::python {
namespace {

// An N x 3 float32 array of `points` (a copy).
py::array_t<float> points_array(const std::vector<Eigen::Vector3f>& points) {
  py::array_t<float> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) o(i, k) = points[i][k];
  return out;
}

// The check `lmk capture` runs in the capture scene (search/capture_check.h), as a dict: whether
// the landmark is distinctive, found itself, the other places it matches, how it can slide within
// the noise, and the findings stored with it. With `look_alikes` false only what needs no search.
py::object verdict(const PointCloud& scene, Landmark& landmark, bool look_alikes) {
  FindSettings find;
  find.scene.up = landmark.up;  // the capture frame is the scene frame
  CaptureCheck check;
  {
    const py::gil_scoped_release release;
    check = check_capture(landmark, &scene, find, look_alikes);
  }
  landmark.findings = check.findings;
  if (!look_alikes) return py::none();
  py::dict d;
  const bool searched = check.look_alikes.has_value();  // not for a flat landmark
  py::list others;
  if (searched) {
    for (const Match& m : check.look_alikes->other_instances)
      others.append(json_to_python(detail::match_to_json(m)));
  }
  d["distinctive"] = !searched || (check.findings.found_itself && check.findings.look_alikes == 0);
  d["found_itself"] = check.findings.found_itself;
  d["other_instances"] = others;
  d["slides"] = describe_slides(check.slides, landmark.box);
  d["findings"] = json_to_python(detail::capture_findings_to_json(check.findings));
  return d;
}

// Landmark.capture_findings: the .lmk's findings as a dict, or None.
py::object capture_findings(const Landmark& l) {
  if (!l.findings.present) return py::none();
  return json_to_python(detail::capture_findings_to_json(l.findings));
}

}  // namespace

void bind_landmarks(py::module_& m) {
  py::class_<Landmark, std::shared_ptr<Landmark>>(
      m, "Landmark", "A landmark: the points cut out with a box, the box, and its grids.")
      .def_readonly("name", &Landmark::name)
      .def_property_readonly(
          "points", [](const Landmark& l) { return points_array(l.points.points); },
          "The landmark's points in its capture frame, an N x 3 float32 array.")
      .def_property_readonly(
          "box", [](const Landmark& l) { return box_to_dict(l.box); },
          "The box drawn, in the capture frame: {'pose': 4x4, 'size': (3,)}.")
      .def_property_readonly(
          "empty_space", [](const Landmark& l) { return points_array(l.empty_space.centres()); },
          "The centres of the box's voxels observed free at capture (the empty-space grid), an "
          "N x 3 float32 array in the capture frame.")
      .def(
          "distance",
          [](const Landmark& l, const py::array_t<float, py::array::forcecast>& points) {
            if (points.ndim() != 2 || points.shape(1) != 3) {
              throw py::value_error("points: must be an N x 3 array");
            }
            const auto p = points.unchecked<2>();
            py::array_t<float> out(points.shape(0));
            auto o = out.mutable_unchecked<1>();
            const DistanceField::Sampler sampler = l.distance.sampler();
            for (py::ssize_t i = 0; i < points.shape(0); ++i) {
              o(i) = sampler.distance(Eigen::Vector3f(p(i, 0), p(i, 1), p(i, 2)));
            }
            return out;
          },
          py::arg("points"),
          "The landmark's distance field (the distance grid) at each of N x 3 points of the "
          "capture frame, m; its band's value beyond the band.")
      .def_property_readonly("capture_findings", &capture_findings,
                             "What the capture check found (noise, slide, symmetry_axes, "
                             "look_alikes, warnings...), as stored in the .lmk; None for a "
                             "landmark built without it.")
      .def_property_readonly("view_count", &Landmark::view_count)
      .def_property_readonly("has_colour", [](const Landmark& l) { return l.points.has_colors(); })
      .def(
          "save", [](const Landmark& l, const std::string& path) { save_landmark(path, l); },
          py::arg("path"), "Writes the .lmk file, atomically.");
  m.def(
      "load_landmark", [](const std::string& path) { return load_landmark(path); }, py::arg("path"),
      "Reads a .lmk file, checked as `lmk` checks it.");
  m.def(
      "capture",
      [](const PointCloud& cloud, const py::object& box_pose, const py::object& box_size,
         const std::string& name, bool base_frame, bool check, const py::kwargs& kwargs) {
        const Box box = box_from_arrays(box_pose, box_size, "box");
        CaptureSettings settings;
        settings.base_frame = base_frame;
        // The other capture settings as keywords, named, limited and in the units of `lmk
        // capture`'s flags (leaf_size=0.004), from CaptureSettings's one description.
        set_from_keywords(kwargs, [&settings](const std::string& keyword, const std::string& key,
                                              const std::string& text) {
          if (!set_setting_from_text(settings, key, text, "capture: ")) {
            throw Error("capture: unknown setting '" + keyword + "'");
          }
        });
        Landmark landmark;
        {
          const py::gil_scoped_release release;
          landmark = capture(cloud, box, name, settings);
        }
        py::object checked = verdict(cloud, landmark, check);
        return py::make_tuple(std::make_shared<Landmark>(std::move(landmark)), checked);
      },
      py::arg("cloud"), py::arg("box_pose"), py::arg("box_size"), py::kw_only(), py::arg("name"),
      py::arg("base_frame") = false, py::arg("check") = true,
      "Cuts a landmark out of `cloud` with the box (a 4x4 pose and three sides, m, in the cloud's "
      "frame). `base_frame`: the cloud is in a robot base frame, whose +z is up. Returns "
      "(landmark, verdict): the verdict of `lmk capture`'s checks (distinctive, found_itself, "
      "other_instances, slides, findings), or None with check=False (the findings that need no "
      "search are stored with the landmark either way). Further keywords are `lmk capture`'s "
      "settings (leaf_size, min_points, distance_band, allow_flat, depth_smoothing, ...), in its "
      "flags' units.");
}

}  // namespace lmk::python
