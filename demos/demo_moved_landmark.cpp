// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/demos/detail/demo_moved_landmark.h"

#include "lmk/geometry/error.h"
#include "lmk/pbd/execute.h"
#include "lmk/pbd/watch.h"

namespace lmk::detail {
namespace {

// The simulated PR2, and a person who moves an object once the arm has been sent `move.after`
// trajectories: the robot's commands pass through unchanged.
class MovedWhileRunning : public ForwardingRobot {
 public:
  MovedWhileRunning(SimulatedPr2& robot, DemoWorld& world, const DemoMove& move)
      : ForwardingRobot(robot), world_(world), move_(move) {}

  CallResult send_trajectory(const std::string& group, const JointTrajectory& t) override {
    if (moved_) ++sent_after_move;
    const CallResult r = ForwardingRobot::send_trajectory(group, t);
    if (++sent_ == move_.after) happen();
    return r;
  }

  std::size_t sent_after_move = 0;

 private:
  void happen() {
    const PlacedObject* placed = world_.object(move_.object);
    if (!placed) throw Error("demo: no object '" + move_.object + "' to move");
    const PlacedObject object = *placed;
    world_.remove(object.id);
    if (move_.to) world_.add(object.id, object.model, *move_.to, object.landmarks);
    moved_ = true;
  }

  DemoWorld& world_;
  const DemoMove& move_;
  std::size_t sent_ = 0;
  bool moved_ = false;
};

}  // namespace

MovedRun execute_while_moved(const Program& program, const Plan& plan, SimulatedPr2& robot,
                             DemoWorld& world, const DemoMove& move,
                             const std::map<std::string, Landmark>& landmarks, bool watch,
                             const PlanSettings& planning, std::uint64_t seed) {
  MovedWhileRunning moving(robot, world, move);
  MovedRun run;
  if (!watch) {
    run.report = execute(plan, moving);
    run.executed = plan;
  } else {
    TrackSettings tracking;
    tracking.find = planning.find;
    TrackingWatch eyes(
        plan, landmarks,
        [&](PointCloud& frame) {
          Eigen::Isometry3d T_base_sensor;
          const CallResult r = robot.sensor_pose(T_base_sensor);
          if (r.ok()) frame = world.observe(T_base_sensor, seed++);
          return r;
        },
        tracking);
    WatchedExecution watched =
        execute_watching(program, plan, moving, robot.kinematics(), eyes, {}, planning);
    run.report = std::move(watched.report);
    run.executed = std::move(watched.plan);
    run.noticed = std::move(watched.noticed);
    run.replans = watched.replans;
  }
  run.sent_after_move = moving.sent_after_move;
  return run;
}

}  // namespace lmk::detail
