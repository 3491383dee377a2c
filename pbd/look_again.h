// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Look again (issue #46): when a program's landmark is missing, or found but below the confidence
// cut, the robot does not refuse at once. It points its head where a second look can settle it,
// takes another frame, fuses it with what it saw (occupancy/tsdf_volume.h) and plans again; after
// at most `max_looks` further frames it refuses as plan() does, naming every look.
//
// Where it looks:
// - a doubtful landmark with a competitor: between the two (both in the middle of the view, the
//   search sees each whole and from nearer the line that separates them);
// - a doubtful landmark without one: at it (centred, it is seen whole);
// - a missing landmark: a pattern about the first view, panning by pattern_angle to one side, then
//   the other, further each time (a landmark the image's edge cut is seen whole from one of them).
// An unreachable step is no question of seeing: it is refused at once.
//
// Where the arm would go (issue #60), once the landmarks are settled and motions are checked: a
// motion that passes through space no camera has seen (PlannedArm::unseen), or is refused for
// touching space its frames hid, is looked at first: the head turns there and the motion check
// knows what that frame saw (a shelf's top board above the first view). After `unseen_looks` such
// frames the plan acts on what it saw, and its warnings name what stayed unseen.

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "lmk/landmark/landmark.h"
#include "lmk/pbd/plan.h"
#include "lmk/pbd/robot_interface.h"

namespace lmk {

/// What lets a program look again: a head that can be pointed and the frame it then sees.
class Eyes {
 public:
  virtual ~Eyes() = default;
  /// Points the head at `target` (base frame) and sets `frame` to what it then sees: an organised
  /// cloud in the base frame, its sensor pose (T_cloud_sensor) the head camera's.
  virtual CallResult look_at(const Eigen::Vector3d& target, PointCloud& frame) = 0;
};

struct LookAgainSettings {
  int max_looks = 2;  ///< further frames before refusing; 0 refuses at once, as plan()
  /// The pan of a missing landmark's pattern about the first view, rad (15 degrees): a third of a
  /// Kinect's field of view, so that each look keeps most of the first in sight.
  double pattern_angle = 0.2618;
  /// Further frames where a checked motion would pass through space no camera has seen, or is
  /// refused for space its frames hid; 0 acts on the first view (and warns).
  int unseen_looks = 2;

  /// Throws lmk::Error naming the bad value.
  void validate() const;
};

/// One further look: where the head was pointed and why.
struct Look {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< base frame
  std::string why;
};

struct LookedPlan {
  Plan plan;                ///< the last plan: valid, or the refusal after every look
  std::vector<Look> looks;  ///< the further looks, in order
};

/// plan() on `first` (a frame in the base frame), looking again through `eyes` while the refusal
/// is a missing or doubtful landmark, then where its motions would pass unseen. Each new frame is
/// fused with every frame before it for the search, and given to the motion check. An
/// `eyes` that fails to point or see ends the looking: the last plan stands, and the failure is
/// the last look's `why`.
LookedPlan plan_looking_again(const Program& program,
                              const std::map<std::string, Landmark>& landmarks,
                              const PointCloud& first, const KinematicsInterface& kinematics,
                              const JointState& start, Eyes& eyes,
                              const PlanSettings& settings = {},
                              const LookAgainSettings& looking = {});

/// "after 2 more looks (at (0.61, -0.20, 0.75): between 'bin' and its look-alike; ...)", or "" for
/// none: what a refusal's message adds.
std::string describe_looks(const std::vector<Look>& looks);

}  // namespace lmk
