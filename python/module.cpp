// SPDX-License-Identifier: BSD-3-Clause
// The `lmk` Python module (issue #36): its version, its error type, and the parts defined in
// clouds.cpp, landmarks.cpp, search.cpp, tracking.cpp, evaluation.cpp and
// robot.cpp.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/version.h"

namespace py = pybind11;

PYBIND11_MODULE(_lmk, m) {
  m.doc() = "lmk: custom perceptual landmarks (the C++ library's bindings)";
  m.attr("__version__") = lmk::kVersion;
  // lmk::Error's one-line message, as the CLI prints it, as lmk.Error (a RuntimeError).
  static py::exception<lmk::Error> error(m, "Error", PyExc_RuntimeError);
  error.doc() =
      "An lmk error: a missing or damaged file, a box with no point in it, a refused "
      "registration; its message is the CLI's one line.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const lmk::Error& e) {
      error(e.what());
    } catch (const lmk::Interrupted& e) {
      // An evaluation stopped by Ctrl-C, its finished pairs cached: Python's own interruption.
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    }
  });
  lmk::python::bind_clouds(m);
  lmk::python::bind_landmarks(m);
  lmk::python::bind_search(m);
  lmk::python::bind_tracking(m);
  lmk::python::bind_evaluation(m);
  lmk::python::bind_robot(m, error);
}
