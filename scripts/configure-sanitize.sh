#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Configures the sanitizer build shared by scripts/test.sh and scripts/fuzz.sh: clang-14 with
# AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer's coverage on every target
# (LMK_FUZZ, cmake/LmkSanitizers.cmake).
# Usage: configure-sanitize.sh BUILD_DIR [CMAKE_ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
export CMAKE_GENERATOR=${CMAKE_GENERATOR:-Ninja}  # as scripts/build.sh
# No Python module: an instrumented module loads only into a python3 started with the sanitizer's
# runtime preloaded; the Release suite tests it.
cmake -S . -B "${1:?build directory}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DLMK_FUZZ=ON \
  -DLMK_BUILD_BENCH=OFF -DLMK_WITH_ROS=OFF -DLMK_BUILD_PYTHON=OFF "${@:2}" >/dev/null
