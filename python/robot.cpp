// SPDX-License-Identifier: BSD-3-Clause
// The robot from Python: the simulated PR2's kinematics (FK and IK on arrays), planning a PbD
// program in a scene, and running it on the simulated PR2 (docs/python.md, "Robot"). A plan the
// robot will not carry out raises lmk.Refused with its kind and the CLI's one-line reason.
#include <pybind11/stl.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>

#include "bindings.h"
#include "lmk/pbd/execute.h"
#include "lmk/pbd/internal/plan_json.h"
#include "lmk/pbd/look_again.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/pr2/pr2_robots.h"
#include "lmk/pr2/simulated_pr2.h"

namespace lmk::python {
namespace {

using namespace pybind11::literals;

// A simulated PR2, configured and active, its torso at `torso_height` (m).
std::shared_ptr<SimulatedPr2> simulated_pr2(double torso_height) {
  return std::make_shared<SimulatedPr2>(start_simulated_pr2(torso_height));
}

const KinematicsInterface& kinematics(const SimulatedPr2& robot) { return robot.kinematics(); }

// A Python callable as the robot's eyes (pbd/look_again.h): look(target) points the head at the
// 3-vector `target` (base frame) and returns the lmk.Cloud it then sees, in the base frame. What it
// raises is raised again from lmk.plan, not turned into a refusal: a bug in it is the caller's to
// see.
class PythonEyes : public Eyes {
 public:
  explicit PythonEyes(py::object look) : look_(std::move(look)) {}
  CallResult look_at(const Eigen::Vector3d& target, PointCloud& frame) override {
    const py::gil_scoped_acquire gil;
    try {
      const py::object seen = look_(py::array_t<double>(3, target.data()));
      if (!py::isinstance<PointCloud>(seen)) {
        throw py::type_error("look must return an lmk.Cloud (the frame the head then sees)");
      }
      frame = seen.cast<const PointCloud&>();
      return CallResult::success();
    } catch (...) {
      raised_ = std::current_exception();
      return CallResult::error("look raised");
    }
  }
  /// Raises what look raised, if it did; with the GIL held.
  void raise_if_raised() const {
    if (raised_) std::rethrow_exception(raised_);
  }

 private:
  py::object look_;
  std::exception_ptr raised_;
};

// Takes keyword `name` out of `keywords` when there.
std::optional<py::object> pop_keyword(py::kwargs& keywords, const char* name) {
  if (!keywords.contains(name)) return std::nullopt;
  py::object value = keywords[name];
  PyDict_DelItemString(keywords.ptr(), name);
  return value;
}

// Plans the program file in `scene` for `robot` as it stands, looking again through `look` when
// given; lmk.Refused when the plan is refused, naming every look.
LookedPlan plan_or_refuse(const std::string& program_file, const PointCloud& scene,
                          SimulatedPr2& robot, const py::kwargs& keywords,
                          const py::object& refused) {
  PlanSettings settings;
  // min_confidence is the program's cut (PlanSettings), not the search's: the search keeps every
  // match, and the plan refuses a doubtful one by name (LandmarkDoubtful).
  py::kwargs search = py::reinterpret_steal<py::kwargs>(PyDict_Copy(keywords.ptr()));
  if (const auto cut_value = pop_keyword(search, "min_confidence")) {
    const double cut = py::cast<double>(*cut_value);
    if (!(cut >= 0.0 && cut <= 1.0)) throw py::value_error("min_confidence must be in [0, 1]");
    settings.min_confidence = cut;
  }
  // collisions=True (the default): every motion checked against the scene and the robot (issue
  // #60), as `lmk pbd plan` does; collisions=False as its --no-check-collisions.
  if (const auto collisions = pop_keyword(search, "collisions");
      !collisions || py::cast<bool>(*collisions))
    settings.motion_checker = pr2_motion_checker(robot.kinematics());
  // approach=: m along the gripper's axis before a grasp and after a release (0: none).
  if (const auto approach = pop_keyword(search, "approach")) {
    settings.approach = py::cast<double>(*approach);
    if (!(settings.approach >= 0.0 && settings.approach <= kMaxApproach)) {
      char text[48];
      std::snprintf(text, sizeof(text), "approach must be 0 to %g m", kMaxApproach);
      throw py::value_error(text);
    }
  }
  const std::optional<py::object> look = pop_keyword(search, "look");
  LookAgainSettings looking;
  looking.max_looks = 0;
  looking.unseen_looks = 0;
  const bool eyes_given = look && !look->is_none();
  if (eyes_given) {
    if (!PyCallable_Check(look->ptr())) throw py::type_error("look must be callable: look(target)");
    looking.max_looks = 2;
    looking.unseen_looks = 2;
  }
  // look_again: further frames for a missing or doubtful landmark; unseen_looks: where a checked
  // motion would pass through space no camera has seen.
  for (auto [name, count] : {std::pair{"look_again", &looking.max_looks},
                             std::pair{"unseen_looks", &looking.unseen_looks}}) {
    const auto k = pop_keyword(search, name);
    if (!k) continue;
    *count = py::cast<int>(*k);
    if (*count < 0 || *count > 8)
      throw py::value_error(std::string(name) + " must be 0 to 8 (further frames)");
    if (*count > 0 && !eyes_given)
      throw py::value_error(std::string(name) + " needs look=callable: the head that looks again");
  }
  settings.find = settings_from_keywords(search);
  PythonEyes eyes(look ? *look : py::none());
  LookedPlan result;
  {
    const py::gil_scoped_release release;
    const Program program = load_program(program_file);
    const auto landmarks =
        load_program_landmarks(program, std::filesystem::path(program_file).parent_path().string());
    JointState state;
    robot.read_joint_state(state);
    result = plan_looking_again(program, landmarks, scene, robot.kinematics(), state, eyes,
                                settings, looking);
  }
  eyes.raise_if_raised();
  if (!result.plan.valid()) {
    const std::string looks = describe_looks(result.looks);
    py::object error =
        refused(describe(*result.plan.refusal) + (looks.empty() ? "" : ", " + looks));
    error.attr("kind") = refusal_kind(*result.plan.refusal);
    PyErr_SetObject(refused.ptr(), error.ptr());
    throw py::error_already_set();
  }
  return result;
}

// The plan as `lmk pbd plan --json` gives it, with the further looks when any were taken.
py::object plan_to_python(const LookedPlan& looked) {
  py::object out = json_to_python(detail::plan_to_json(looked.plan));
  if (looked.looks.empty()) return out;
  py::list looks;
  for (const Look& look : looked.looks) {
    looks.append(
        py::dict("target"_a = py::array_t<double>(3, look.target.data()), "why"_a = look.why));
  }
  out["looks"] = looks;
  return out;
}

// lmk.SimulatedPr2: its kinematics (groups, joints, forward and inverse) and joint state.
void bind_simulated_pr2(py::module_& m) {
  py::class_<SimulatedPr2, std::shared_ptr<SimulatedPr2>>(
      m, "SimulatedPr2", "lmk's simulated PR2 (the CLI's --sim), configured and active.")
      .def(py::init(&simulated_pr2), py::arg("torso_height") = 0.0)
      .def("groups", [](const SimulatedPr2& r) { return kinematics(r).groups(); })
      .def(
          "joint_names",
          [](const SimulatedPr2& r, const std::string& group) {
            const auto info = kinematics(r).group(group);
            if (!info) throw py::value_error("no group '" + group + "'");
            std::vector<std::string> names;
            for (const JointInfo& j : info->joints) names.push_back(j.name);
            return names;
          },
          py::arg("group"))
      .def(
          "forward",
          [](const SimulatedPr2& r, const std::string& group, const std::vector<double>& joints) {
            Eigen::Isometry3d T_base_tool;
            const CallResult result = kinematics(r).forward(group, joints, T_base_tool);
            if (!result.ok()) throw py::value_error(result.message);
            return pose_to_array(T_base_tool);
          },
          py::arg("group"), py::arg("joints"),
          "The tool's 4x4 pose in base_link for the group's joint values, in its joint order.")
      .def(
          "inverse",
          [](const SimulatedPr2& r, const std::string& group, const py::object& pose,
             const std::vector<double>& seed) {
            const IkResult ik = kinematics(r).inverse(group, pose_from_array(pose, "pose"), seed);
            return py::dict("success"_a = ik.success, "joints"_a = ik.joints,
                            "position_error"_a = ik.position_error,
                            "rotation_error"_a = ik.rotation_error, "message"_a = ik.message);
          },
          py::arg("group"), py::arg("pose"), py::arg("seed") = std::vector<double>{},
          "IK for a 4x4 tool pose in base_link: {success, joints, position_error (m), "
          "rotation_error (rad), message}.")
      .def("joint_state",
           [](const SimulatedPr2& r) {
             JointState state;
             r.read_joint_state(state);
             py::dict d;
             for (std::size_t i = 0; i < state.names.size(); ++i)
               d[py::str(state.names[i])] = state.positions[i];
             return d;
           })
      .def_property_readonly("time", &SimulatedPr2::time, "Simulated seconds so far.");
}

}  // namespace

void bind_robot(py::module_& m, const py::object& error) {
  // lmk.Refused(lmk.Error): a valid request the robot will not carry out; `kind` is
  // "landmark-not-found", "landmark-doubtful", "unreachable" or "collision", as `lmk pbd plan
  // --json` names it.
  const py::object refused = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "lmk.Refused",
      "A plan the robot will not carry out; `kind` says why "
      "('landmark-not-found', 'landmark-doubtful', 'unreachable', 'collision').",
      error.ptr(), nullptr));
  m.attr("Refused") = refused;

  bind_simulated_pr2(m);

  m.def(
      "plan",
      [refused](const std::string& program, const PointCloud& scene, SimulatedPr2& robot,
                const py::kwargs& kwargs) {
        return plan_to_python(plan_or_refuse(program, scene, robot, kwargs, refused));
      },
      py::arg("program"), py::arg("scene"), py::arg("robot"),
      "Plans a program file (its landmarks beside it) in `scene` (base frame) for `robot` as it "
      "stands, as `lmk pbd plan --json` does; raises lmk.Refused when the robot would not carry "
      "it out (kind 'landmark-doubtful' for a landmark below min_confidence, default 0.8). "
      "look=callable(target) -> lmk.Cloud is a head that can look again: when a landmark is "
      "missing or doubtful it is pointed at the 3-vector target (base frame) and returns what it "
      "then sees, fused with the frames before (at most look_again times, default 2; the plan's "
      "'looks' lists them). collisions=True (the default) checks every motion against the scene, "
      "the space it hides and the robot, plans around what it would touch, or refuses (kind "
      "'collision'), as `lmk pbd plan` does; collisions=False moves along straight joint lines "
      "unchecked (--no-check-collisions). approach=0.1 reaches a grasp from that far back along "
      "the gripper's axis and backs off a release as far, m (0: none; each such motion is a step "
      "of its own, 'phase' 'approach' or 'retreat'). Search settings are keywords as for "
      "lmk.find.");
  m.def(
      "run",
      [refused](const std::string& program, const PointCloud& scene, SimulatedPr2& robot,
                const py::kwargs& kwargs) {
        const Plan planned = plan_or_refuse(program, scene, robot, kwargs, refused).plan;
        ExecutionReport report;
        {
          const py::gil_scoped_release release;
          report = execute(planned, robot);
        }
        return py::dict(
            "completed"_a = report.completed, "steps_completed"_a = report.steps_completed,
            "steps_total"_a = report.steps_total, "error"_a = report.error, "log"_a = report.log);
      },
      py::arg("program"), py::arg("scene"), py::arg("robot"),
      "Plans as lmk.plan, then executes on the simulated PR2 (`lmk pbd run --sim`): "
      "{completed, steps_completed, steps_total, error, log}.");
}

}  // namespace lmk::python
