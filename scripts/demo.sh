#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Quick start 1: install, build, and run lmk's main job on built-in data: the paper's evaluation.
# `lmk eval` renders the built-in 'paper' benchmark (the paper's 17 scene types seen by a simulated
# Kinect, 11 landmarks captured in their demonstration scenes) on first use, searches every
# landmark in every scene with the fast method, and prints the paper's precision/recall table per
# setting and assumption. A few minutes on 2 cores; results are cached, so a second run is instant.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --tool
build=${LMK_BUILD_DIR:-build}
"$build/tools/lmk" --version
echo
# --timings: the table's s/search column, the median wall time per search (left out otherwise, so
# that the table is the same byte for byte from run to run).
"$build/tools/lmk" eval --timings --report "$build/demo/report"
