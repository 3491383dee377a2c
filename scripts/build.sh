#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the dependencies (if missing) and builds lmk in Release into ${LMK_BUILD_DIR:-build}.
#   build.sh [CMAKE_ARGS...]         everything: the libraries, the lmk tool, lmk_node (with ROS),
#                                    the Python module, the tests and the benchmarks
#   build.sh --tool [CMAKE_ARGS...]  the lmk tool alone and only its dependencies: what the demos run
# Extra arguments go to CMake's configure step, e.g. -DLMK_WERROR=ON. Both share one build
# directory: each says which parts it wants, so that one never inherits the other's choice.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${LMK_BUILD_DIR:-build}
# Ninja compiles any target's files while others link, keeping both cores busy where make's
# target-by-target order left one idle (docs/developing.md, "CI's time"). CMake reads this only for a
# new build directory: one configured with make stays so.
export CMAKE_GENERATOR=${CMAKE_GENERATOR:-Ninja}
if [ "${1:-}" = --tool ]; then
  shift
  bash scripts/install-deps.sh --tool
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DLMK_BUILD_TESTS=OFF -DLMK_BUILD_BENCH=OFF \
    -DLMK_BUILD_PYTHON=OFF -DLMK_WITH_ROS=OFF "$@"
  cmake --build "$build" -j2 --target lmk
else
  bash scripts/install-deps.sh
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DLMK_BUILD_TESTS=ON -DLMK_BUILD_BENCH=ON \
    -DLMK_BUILD_PYTHON=ON -DLMK_WITH_ROS=AUTO "$@"
  cmake --build "$build" -j2
fi
