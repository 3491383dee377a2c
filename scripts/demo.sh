#!/usr/bin/env bash
# Quick start 1: install, build, and run lmk's main job on built-in data.
# Until the landmark search lands, the main job renders a synthetic tabletop frame with the
# simulated Kinect and describes it; later it becomes the evaluation (lmk eval).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
build=${LMK_BUILD_DIR:-build}
lmk="$build/tools/lmk"
out="$build/demo"
mkdir -p "$out"
"$lmk" --version
echo
"$lmk" gen "$out/tabletop.pcd" --seed 1
echo
"$lmk" info "$out/tabletop.pcd"
