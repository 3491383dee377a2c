#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian 12 packages lmk needs.
#   install-deps.sh          everything: to build, test and benchmark all of lmk
#   install-deps.sh --tool   only what the lmk tool needs to build and run (the demos)
# Idempotent: when every package is already installed it does nothing (no apt-get update).
set -euo pipefail

case "${1:-}" in
  ""|--tool) ;;
  *) echo "install-deps.sh: unknown option '$1' (--tool or nothing)" >&2; exit 2 ;;
esac

# The lmk tool: its libraries and `lmk serve`.
tool_packages=(
  # toolchain; Ninja keeps both cores compiling while targets link (scripts/build.sh)
  build-essential cmake ninja-build pkg-config git
  # the libraries lmk is built on (docs/developing.md)
  libeigen3-dev libopenvdb-dev libceres-dev libpcl-dev libcgal-dev liburdfdom-dev
  libnanoflann-dev libtbb-dev nlohmann-json3-dev libcli11-dev
  # planning arm motions around what the camera sees (pr2/robot_motion_checker.h), and the pairs
  # of links a robot's SRDF says may touch (pr2/srdf.h)
  libompl-dev libtinyxml2-dev
  # RGB-D depth and colour images (geometry/depth_image.h), the report's PNG pictures
  libpng-dev
  # Debian's PCL config pulls in VTK, whose config needs MPI's C bindings
  mpi-default-dev
  # lmk serve: the HTTP server, and three.js for its page (read from /usr/share/javascript/three)
  libcpp-httplib-dev libjs-three
)

# Everything else: tests, benchmarks, the format check, the sanitizer and fuzz builds, ROS, Python
# and Slurm.
more_packages=(
  # the format check (scripts/check-format.sh), and the function-length check's extents
  # (tests/style/check_function_length.py)
  clang-format universal-ctags
  # tests and benchmarks
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  # the evaluation report's rendering test and lmk serve's browser test (headless Chromium driven
  # over the DevTools protocol by Node.js with Debian's WebSocket module)
  chromium nodejs node-ws
  # the sanitizer build and the fuzz targets (scripts/fuzz.sh): clang with libFuzzer's runtime
  clang-14 libclang-rt-14-dev
  # the ThreadSanitizer run fetches and builds Debian's oneTBB source (scripts/build-tbb-tsan.sh)
  curl xz-utils
  # ROS 1 for lmk::ros and lmk_node (docs/ros.md): roscpp, the message packages and generators,
  # TF, actionlib, interactive markers, rosbag, and the master and tools its tests start
  ros-core-dev libroscpp-dev libactionlib-dev libactionlib-msgs-dev libsensor-msgs-dev
  libgeometry-msgs-dev libvisualization-msgs-dev libtrajectory-msgs-dev libstd-srvs-dev
  libtf2-ros-dev libtf2-eigen-dev libinteractive-markers-dev librosbag-dev libpcl-conversions-dev
  python3-gencpp python3-genmsg ros-message-generation python3-rosmaster python3-roslaunch
  python3-rostest python3-rospy python3-rosbag catkin python3-catkin-pkg
  # roslib: lmk pbd run --ros finds robot_description's meshes through the package paths
  libroslib-dev
  # lmk_msgs from Python and the shell: genpy generates it; rosservice and rospy's examples need
  # the geometry messages it embeds
  python3-genpy python3-rosservice python3-geometry-msgs
  # the Python module (python/, docs/python.md) and its tests
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
  # lmk slurm's test starts a one-node Slurm cluster (tests/cluster/slurm_test.sh)
  slurm-wlm munge
)

packages=("${tool_packages[@]}")
[ "${1:-}" = --tool ] || packages+=("${more_packages[@]}")

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  sudo=sudo
else
  sudo=
fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
