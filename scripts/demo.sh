#!/usr/bin/env bash
# Quick start 1: install, build, and run lmk's main job on built-in data: render a tabletop scene
# with the simulated Kinect, capture the carton on it as a landmark, and find it again with the
# paper's reference search. (The evaluation over the benchmark replaces this once it lands.)
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
echo
# The carton of seed 1 as lmk gen prints it (centre, 7 x 7 x 19 cm, yaw -156 deg), drawn with 2 cm
# of free space around and above it, and its bottom just above the table top.
"$lmk" capture "$out/tabletop.pcd" --box-center -0.301 0.236 0.826 --box-rpy 0 0 -156 \
  --box-size 0.11 0.11 0.21 --name carton -o "$out/carton.lmk"
"$lmk" landmark show "$out/carton.lmk"
echo
# 150 seeds rather than the paper's 1000 keep the reference search under a minute. Expect the
# carton, and also the table's square leg: to the paper's method a box post looks like a carton.
"$lmk" find "$out/tabletop.pcd" "$out/carton.lmk" --max-seeds 150
