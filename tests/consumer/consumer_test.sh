#!/usr/bin/env bash
# Installs this build into a scratch prefix, then configures, builds and runs a separate consumer
# project against it with find_package(lmk).
# Usage: consumer_test.sh BUILD_DIR CONSUMER_SOURCE_DIR CMAKE
set -eu
build=$1
source=$2
cmake=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$cmake" --install "$build" --prefix "$work/prefix" >"$work/install.log"
"$cmake" -S "$source" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log"
"$cmake" --build "$work/build" -j2 >"$work/build.log"
"$work/build/consumer"
