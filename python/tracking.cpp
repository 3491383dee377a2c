// SPDX-License-Identifier: BSD-3-Clause
// lmk.Tracker: landmarks followed through frames (search/tracker.h, issue #48), with the search's
// settings as keywords as lmk.find takes them; the GIL released while a frame is tracked.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "bindings.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/search/internal/track_json.h"
#include "lmk/search/tracker.h"

namespace lmk::python {
namespace {

// `lmk track --json`'s line (search/internal/track_json.h), with the pose (the capture frame in
// the frame) and the box as arrays too, as lmk.find gives a match's.
py::dict tracked_to_python(const TrackedLandmark& t) {
  py::dict d = json_to_python(detail::tracked_landmark_to_json(t));
  if (t.match) {
    d["pose"] = pose_to_array(t.match->T_scene_capture);
    d["box"] = box_to_dict(t.match->box);
  }
  return d;
}

CameraMotion camera_motion_named(const std::string& name) {
  if (const std::optional<CameraMotion> motion = setting_value_named<CameraMotion>(name))
    return *motion;
  throw py::value_error("camera_motion must be 'none' or 'estimated', not '" + name + "'");
}

}  // namespace

void bind_tracking(py::module_& m) {
  py::class_<Tracker>(m, "Tracker",
                      "Landmarks followed through a stream of frames: each predicted from its "
                      "last poses, aligned locally, and searched again when lost (docs/python.md, "
                      "\"Tracking\").")
      .def(py::init([](const std::vector<std::shared_ptr<Landmark>>& landmarks,
                       double follow_margin, double search_margin, double follow_threshold_factor,
                       const std::string& camera_motion, const py::kwargs& kwargs) {
             TrackSettings settings;
             settings.find = settings_from_keywords(kwargs);
             settings.follow_margin = follow_margin;
             settings.search_margin = search_margin;
             settings.follow_threshold_factor = follow_threshold_factor;
             settings.camera_motion = camera_motion_named(camera_motion);
             std::vector<std::shared_ptr<const Landmark>> shared;
             shared.assign(landmarks.begin(), landmarks.end());
             try {
               return Tracker(std::move(shared), settings);
             } catch (const Error& e) {
               throw py::value_error(e.what());
             }
           }),
           py::arg("landmarks"), py::kw_only(),
           py::arg("follow_margin") = TrackSettings{}.follow_margin,
           py::arg("search_margin") = TrackSettings{}.search_margin,
           py::arg("follow_threshold_factor") = TrackSettings{}.follow_threshold_factor,
           py::arg("camera_motion") = setting_name(TrackSettings{}.camera_motion),
           "A tracker of `landmarks`. Search settings are keywords as lmk.find takes them; "
           "follow_margin (m) grows the predicted box the frame is searched in, search_margin "
           "(m) the region a lost landmark is searched in first, follow_threshold_factor how many "
           "times the error threshold a followed match may reach, camera_motion 'none' (the frames "
           "share a fixed frame) or 'estimated' (each frame registered onto the one before).")
      .def(
          "update",
          [](Tracker& tracker, const PointCloud& frame) {
            std::vector<TrackedLandmark> now;
            {
              const py::gil_scoped_release release;
              now = tracker.update(frame);
            }
            py::list out;
            for (const TrackedLandmark& t : now) out.append(tracked_to_python(t));
            return out;
          },
          py::arg("frame"),
          "The landmarks in the next frame, in the order given: each a dict as `lmk track --json` "
          "writes its line, with 'landmark', 'state' ('found', 'tracking', 'lost', 'found "
          "again'), 'seconds', and when found the box's 'position' and 'quaternion', 'error' and "
          "'confidence' (None where no calibration applies), with 'pose' (4x4) and 'box' as "
          "lmk.find's matches have them; or 'lost_because'.");
}

}  // namespace lmk::python
