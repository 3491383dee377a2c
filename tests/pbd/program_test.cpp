// SPDX-License-Identifier: BSD-3-Clause
// Program files: round trips, and a clear error for every way a program can be wrong.

#include "lmk/pbd/program.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

Program two_arm_program() {
  Program p;
  p.name = "hang tool";
  p.landmarks = {{"rack", "rack.lmk"}, {"tool", "landmarks/tool.lmk"}};
  // The tool's handle is round: any turn about its axis is the same handle.
  p.landmarks[1].demonstration = pose_from_xyz_rpy({0.7, -0.1, 0.9}, {0, 0, 0.2});
  p.landmarks[1].symmetry = Symmetry{Eigen::Vector3d::UnitZ(), 0};
  p.landmarks[1].select = InstancePolicy::kNearestToDemonstration;
  ProgramStep reach;
  reach.right = ArmTarget{"tool", pose_from_xyz_rpy({0.1, -0.02, 0.15}, {0.3, -0.2, 1.1}),
                          GripperAction::kOpen};
  reach.duration = 2.5;
  ProgramStep grasp;
  grasp.right = ArmTarget{"tool", pose_from_xyz_rpy({0.1, -0.02, 0.05}, {0.3, -0.2, 1.1}),
                          GripperAction::kClose};
  grasp.left =
      ArmTarget{kBaseFrame, pose_from_xyz_rpy({0.5, 0.4, 0.9}, {0, 0, 0}), GripperAction::kOpen};
  ProgramStep place;
  place.right =
      ArmTarget{"rack", pose_from_xyz_rpy({0, 0.05, 0.2}, {0, 1.2, 0}), GripperAction::kOpen};
  p.steps = {reach, grasp, place};
  return p;
}

void expect_same(const Program& a, const Program& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.landmarks.size(), b.landmarks.size());
  for (std::size_t i = 0; i < a.landmarks.size(); ++i) {
    EXPECT_EQ(a.landmarks[i].name, b.landmarks[i].name);
    EXPECT_EQ(a.landmarks[i].file, b.landmarks[i].file);
    EXPECT_EQ(a.landmarks[i].select, b.landmarks[i].select);
    ASSERT_EQ(a.landmarks[i].demonstration.has_value(), b.landmarks[i].demonstration.has_value());
    if (a.landmarks[i].demonstration) {
      EXPECT_TRUE(a.landmarks[i].demonstration->isApprox(*b.landmarks[i].demonstration, 1e-12));
    }
    ASSERT_EQ(a.landmarks[i].symmetry.axis.has_value(), b.landmarks[i].symmetry.axis.has_value());
    if (a.landmarks[i].symmetry.axis) {
      EXPECT_EQ(*a.landmarks[i].symmetry.axis, *b.landmarks[i].symmetry.axis);
      EXPECT_EQ(a.landmarks[i].symmetry.order, b.landmarks[i].symmetry.order);
    }
  }
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t i = 0; i < a.steps.size(); ++i) {
    EXPECT_EQ(a.steps[i].duration, b.steps[i].duration);
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      const auto& x = a.steps[i].arm(arm);
      const auto& y = b.steps[i].arm(arm);
      ASSERT_EQ(x.has_value(), y.has_value()) << "step " << i << " " << arm_name(arm);
      if (!x) continue;
      EXPECT_EQ(x->frame, y->frame);
      EXPECT_EQ(x->gripper, y->gripper);
      EXPECT_TRUE(x->T_frame_ee.isApprox(y->T_frame_ee, 1e-12));
    }
  }
}

TEST(ProgramFile, RoundTripsThroughAFile) {
  const test::ScratchDir dir;
  const Program p = two_arm_program();
  save_program(dir.file("p.json"), p);
  expect_same(p, load_program(dir.file("p.json")));
}

TEST(ProgramFile, AnEmptyProgramRoundTrips) {
  Program p;
  p.name = "nothing yet";
  expect_same(p, program_from_json(program_to_json(p), "mem"));
}

// Issue #48: what a program asks a watching execution to do when a landmark moves is kept; a
// program that says nothing writes no field (older files and tools read it unchanged).
TEST(ProgramFile, WhatToDoWhenALandmarkMovesRoundTrips) {
  Program p = two_arm_program();
  EXPECT_EQ(program_to_json(p).find("when_landmark_moves"), std::string::npos);
  EXPECT_FALSE(program_from_json(program_to_json(p), "mem").when_landmark_moves);
  for (WhenMoved when : {WhenMoved::kStop, WhenMoved::kReplan}) {
    p.when_landmark_moves = when;
    const Program back = program_from_json(program_to_json(p), "mem");
    ASSERT_TRUE(back.when_landmark_moves);
    EXPECT_EQ(*back.when_landmark_moves, when);
  }
  std::string text = program_to_json(p);
  text.replace(text.find("\"re-plan\""), 9, "\"adapt\"");
  try {
    program_from_json(text, "prog.json");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find(
            "when_landmark_moves: unknown answer to a moved landmark 'adapt' (re-plan, stop)"),
        std::string::npos)
        << e.what();
  }
}

// Each case edits a valid program's JSON and names a word the error must contain.
struct BadProgram {
  const char* what;
  const char* from;
  const char* to;
  const char* message;
};

TEST(ProgramFile, EveryValidationErrorSaysWhatAndWhere) {
  const std::string good = program_to_json(two_arm_program());
  const std::vector<BadProgram> cases = {
      {"unknown landmark", "\"frame\": \"rack\"", "\"frame\": \"shelf\"",
       "steps[2].right: unknown landmark 'shelf'"},
      {"bad quaternion", "\"quaternion\": [", "\"quaternion\": [2.0, ",
       "landmarks[1].demonstration.quaternion"},
      {"wrong version", "\"version\": 1", "\"version\": 7", "version 7 is not supported"},
      {"version as text", "\"version\": 1", "\"version\": \"1\"",
       "version: must be a whole number such as 1, not \"1\""},
      {"missing version", ",\n  \"version\": 1", "", "missing field 'version'"},
      {"wrong format", "\"lmk-program\"", "\"lmk-dataset\"", "format"},
      {"bad gripper", "\"gripper\": \"close\"", "\"gripper\": \"half\"",
       "must be \"open\" or \"close\""},
      {"negative duration", "\"duration\": 2.5", "\"duration\": -1", "positive"},
      {"landmark without file", "\"file\": \"rack.lmk\"", "\"file\": \"\"", "'file'"},
      {"landmark called base", "\"name\": \"rack\"", "\"name\": \"base\"", "base"},
      // Names are printed: an escape sequence in one would rewrite the terminal (issue #47).
      {"escape in a name", "\"name\": \"rack\"", "\"name\": \"ra\\u001b[2Jck\"",
       "'name' must be printable text, not 'ra\\x1b[2Jck'"},
      {"unknown policy", "\"nearest-to-demonstration\"", "\"closest\"",
       "landmarks[1].select: unknown instance policy 'closest'"},
      {"symmetry of order one", "\"order\": 0", "\"order\": 1", "order must be 0"},
      {"zero symmetry axis", "\"axis\": [\n          0.0,\n          0.0,\n          1.0",
       "\"axis\": [0, 0, 0", "symmetry axis must be a finite, non-zero vector"},
      {"symmetry without demonstration", "\"demonstration\"", "\"shown\"",
       "needs its demonstrated pose"},
  };
  for (const BadProgram& c : cases) {
    std::string text = good;
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.what;
    text.replace(at, std::string(c.from).size(), c.to);
    try {
      program_from_json(text, "prog.json");
      ADD_FAILURE() << c.what << ": accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("prog.json"), std::string::npos) << c.what << ": " << message;
      EXPECT_NE(message.find(c.message), std::string::npos) << c.what << ": " << message;
    }
  }
}

TEST(ProgramFile, AStepWithoutAnArmIsRefused) {
  const std::string text =
      R"({"format": "lmk-program", "version": 1, "name": "p", "landmarks": [],
          "steps": [{"duration": 1.0}]})";
  EXPECT_THROW(
      {
        try {
          program_from_json(text, "p.json");
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("steps[0]: moves neither arm"), std::string::npos)
              << e.what();
          throw;
        }
      },
      Error);
}

TEST(ProgramFile, NotJsonAndMissingFilesAreClearErrors) {
  EXPECT_THROW(program_from_json("{nope", "p.json"), Error);
  EXPECT_THROW(load_program("/nonexistent/lmk/program.json"), Error);
}

TEST(Program, ValidationCatchesWhatCodeCanBuild) {
  Program p = two_arm_program();
  EXPECT_NO_THROW(validate_program(p));
  p.landmarks.push_back({"rack", "other.lmk"});
  EXPECT_THROW(validate_program(p), Error);  // a landmark twice
  p = two_arm_program();
  p.steps[1].left->T_frame_ee.linear() *= 2.0;  // not a rotation
  EXPECT_THROW(validate_program(p), Error);
  p = two_arm_program();
  p.name.clear();
  EXPECT_THROW(validate_program(p), Error);
}

TEST(ProgramFile, SavingAnInvalidProgramLeavesTheOldFile) {
  const test::ScratchDir dir;
  save_program(dir.file("p.json"), two_arm_program());
  Program bad = two_arm_program();
  bad.steps[0].right->frame = "missing";
  EXPECT_THROW(save_program(dir.file("p.json"), bad), Error);
  expect_same(two_arm_program(), load_program(dir.file("p.json")));
}

}  // namespace
}  // namespace lmk
