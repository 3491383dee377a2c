#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# lmk in a catkin workspace (issue #18), as a PR2 PbD stack would use it:
#   1. lmk's package.xml parses, and its version is CMake's project version;
#   2. catkin orders a workspace holding lmk and a consumer package lmk first (it reads the
#      dependency from the manifests);
#   3. catkin_make_isolated builds the consumer package against this build's installed lmk, and
#      the consumer runs.
# With LMK_CATKIN_FULL=1, step 3 builds lmk itself from source in the workspace as well (several
# minutes; not in CI, where step 3 uses the installed tree instead).
# Usage: catkin_test.sh BUILD_DIR SOURCE_DIR CMAKE PROJECT_VERSION
set -euo pipefail
build=$1
source=$(cd "$2" && pwd)
cmake=$3
version=$4
# Debian's catkin runs python3 at configure time: use Debian's, whatever else is on PATH.
python=/usr/bin/python3
if ! command -v catkin_make_isolated >/dev/null; then
  echo "catkin_test.sh: catkin is not installed (scripts/install-deps.sh installs it); skipped"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

manifest_version=$("$python" -c 'import sys
from catkin_pkg.package import parse_package
print(parse_package(sys.argv[1]).version)' "$source/package.xml")
if [ "$manifest_version" != "$version" ]; then
  echo "catkin_test.sh: package.xml says $manifest_version, CMakeLists.txt says $version" >&2
  exit 1
fi
echo "catkin_test.sh: package.xml parses; version $manifest_version"

mkdir -p "$work/ws/src"
ln -s "$source" "$work/ws/src/lmk"
ln -s "$source/tests/catkin_consumer" "$work/ws/src/lmk_catkin_consumer"
order=$(catkin_topological_order "$work/ws/src" --only-names | tr '\n' ' ')
if [ "$order" != "lmk lmk_catkin_consumer " ]; then
  echo "catkin_test.sh: catkin orders the workspace '$order'" >&2
  exit 1
fi
echo "catkin_test.sh: workspace order: $order"

args=(-C "$work/ws" --install -j2 --cmake-args -DPYTHON_EXECUTABLE="$python"
      -DLMK_BUILD_TESTS=OFF -DLMK_BUILD_BENCH=OFF)
if [ "${LMK_CATKIN_FULL:-0}" != 1 ]; then
  rm "$work/ws/src/lmk"
  "$cmake" --install "$build" --prefix "$work/prefix" >"$work/install.log"
  export CMAKE_PREFIX_PATH="$work/prefix${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"
  export LD_LIBRARY_PATH="$work/prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
if ! catkin_make_isolated "${args[@]}" >"$work/catkin.log" 2>&1; then
  tail -40 "$work/catkin.log" >&2
  echo "catkin_test.sh: catkin_make_isolated failed (above)" >&2
  exit 1
fi
# The workspace's environment, as a user's shell would have it (setup.bash reads unset variables).
set +u
source "$work/ws/install_isolated/setup.bash"
set -u
"$work/ws/install_isolated/lib/lmk_catkin_consumer/lmk_catkin_consumer"
client="$work/ws/install_isolated/lib/lmk_catkin_consumer/lmk_catkin_consumer_client"
if [ -x "$client" ]; then "$client"; fi
