// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of a PbD plan, which `lmk pbd plan --json` prints and `lmk serve` answers with: the
// landmarks located, every step's targets in the base frame with their IK solutions, and the
// refusal if there is one. Header-only; internal/: shared within
// lmk, not installed.

#include <nlohmann/json.hpp>

#include "lmk/json/pose_json.h"
#include "lmk/pbd/plan.h"
#include "lmk/search/internal/confidence_json.h"

namespace lmk::detail {

inline nlohmann::json plan_to_json(const Plan& plan) {
  nlohmann::json landmarks = nlohmann::json::array(), steps = nlohmann::json::array();
  for (const LocatedLandmark& l : plan.landmarks) {
    nlohmann::json j = pose_to_json(l.T_base_landmark);
    j["name"] = l.name;
    j["error"] = l.match.error;
    j["found"] = l.found;
    j["eligible"] = l.eligible;
    j["policy"] = instance_policy_name(l.policy);
    j["seconds"] = l.seconds;
    j["confidence"] = finite_or_null(l.match.confidence.probability);
    landmarks.push_back(j);
  }
  for (const PlannedStep& s : plan.steps) {
    nlohmann::json arms = nlohmann::json::array();
    for (const PlannedArm& a : s.arms) {
      nlohmann::json j = pose_to_json(a.T_base_ee);
      j["arm"] = arm_name(a.arm);
      j["frame"] = a.frame;
      j["gripper"] = gripper_action_name(a.gripper);
      j["joints"] = a.ik.joints;
      j["position_error_m"] = a.ik.position_error;
      j["rotation_error_rad"] = a.ik.rotation_error;
      // Issue #60: the motion's check, where motions are checked.
      j["clearance_m"] = finite_or_null(a.clearance);
      j["planned_around"] = a.planned_around;
      if (a.planned_around)
        j["planner"] = {{"seconds", a.planning_seconds}, {"checks", a.planning_checks}};
      nlohmann::json near = nlohmann::json::array();
      for (const Eigen::Vector3d& p : a.intended.near) near.push_back(vector_to_json(p));
      j["intended_contact"] = {{"near", near}, {"radius_m", a.intended.radius}};
      // Where the motion passes through space no camera has seen, in the order the arm gets there.
      nlohmann::json unseen = nlohmann::json::array();
      for (const Eigen::Vector3d& p : a.unseen) unseen.push_back(vector_to_json(p));
      j["unseen"] = unseen;
      arms.push_back(j);
    }
    steps.push_back({{"step", s.index},
                     {"phase", phase_name(s.phase)},
                     {"duration", s.duration},
                     {"arms", arms}});
  }
  nlohmann::json j = {{"program", plan.program},
                      {"valid", plan.valid()},
                      {"landmarks", landmarks},
                      {"steps", steps},
                      {"warnings", plan.warnings}};
  if (plan.refusal) {
    j["refusal"] = {{"kind", refusal_kind(*plan.refusal)}, {"message", describe(*plan.refusal)}};
    if (const auto* blocked = std::get_if<Blocked>(&*plan.refusal)) {
      const MotionContact& c = blocked->contact;
      j["refusal"]["step"] = blocked->step;
      j["refusal"]["phase"] = phase_name(blocked->phase);
      j["refusal"]["arm"] = arm_name(blocked->arm);
      j["refusal"]["contact"] = {{"link", c.link},
                                 {"obstacle", c.obstacle},
                                 {"distance_m", c.distance},
                                 {"where", vector_to_json(c.where)},
                                 {"along", c.at}};
      j["refusal"]["planner"] = blocked->planner;
    }
    if (const auto* doubtful = std::get_if<LandmarkDoubtful>(&*plan.refusal)) {
      nlohmann::json& r = j["refusal"];
      r["landmark"] = doubtful->landmark;
      r["confidence"] = finite_or_null(doubtful->confidence);
      r["min_confidence"] = doubtful->min_confidence;
      r["doubt"] = doubtful->doubt;
      if (doubtful->competitor.kind != Competitor::Kind::none) {
        r["competitor"] = {{"kind", setting_name(doubtful->competitor.kind)},
                           {"distance", doubtful->competitor.distance},
                           {"angle", doubtful->competitor.angle}};
      }
    }
  }
  return j;
}

}  // namespace lmk::detail
