// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A test fixture over a small generated dataset: two simple scenes (a bowl and a cup; three balls)
// and their three landmarks, 6 pairs, generated once per suite.

#include <gtest/gtest.h>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/eval/evaluation.h"
#include "tests/support/test_support.h"

namespace lmk::test {

class SimpleScenes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir();
    GenerateOptions options;
    options.types = {"simple/bowl_and_cup", "simple/three_balls"};
    dataset_ = new Dataset(generate_benchmark_dataset(dir_->path().string(), "paper", options));
  }
  static void TearDownTestSuite() {
    delete dataset_;
    delete dir_;
    dataset_ = nullptr;
    dir_ = nullptr;
  }
  static Evaluation run(EvaluationSettings settings) {
    return evaluate(dir_->path().string(), *dataset_, settings);
  }
  static inline ScratchDir* dir_ = nullptr;
  static inline Dataset* dataset_ = nullptr;
};

}  // namespace lmk::test
