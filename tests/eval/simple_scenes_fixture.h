// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A test fixture over a small generated dataset: two simple scenes (a bowl and a cup; three balls)
// and their three landmarks, 6 pairs. Generated once per CTest run (test::shared_run_data), as each
// test is a process of its own; the tests only read it, and copy it to change it.

#include <gtest/gtest.h>

#include <filesystem>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/datasets/dataset.h"
#include "lmk/eval/evaluation.h"
#include "tests/support/test_support.h"

namespace lmk::test {

class SimpleScenes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(
        shared_run_data("simple-scenes", [](const std::filesystem::path& dir) {
          GenerateOptions options;
          options.types = {"simple/bowl_and_cup", "simple/three_balls"};
          generate_benchmark_dataset(dir.string(), "paper", options);
        }));
    dataset_ = new Dataset(load_dataset(dir_->string()));
  }
  static void TearDownTestSuite() {
    delete dataset_;
    delete dir_;
    dataset_ = nullptr;
    dir_ = nullptr;
  }
  static Evaluation run(EvaluationSettings settings) {
    return evaluate(dir_->string(), *dataset_, settings);
  }
  static inline std::filesystem::path* dir_ = nullptr;
  static inline Dataset* dataset_ = nullptr;
};

}  // namespace lmk::test
