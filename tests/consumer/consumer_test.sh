#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs this build into a scratch prefix, then configures, builds and runs a separate consumer
# project against it with find_package(lmk). With FORBIDDEN (an extended regex), the consumer must
# not load any library whose name matches it: a robot deployment links no benchmark code.
# Usage: consumer_test.sh BUILD_DIR CONSUMER_SOURCE_DIR CMAKE [FORBIDDEN]
set -eu
build=$1
source=$2
cmake=$3
forbidden=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$cmake" --install "$build" --prefix "$work/prefix" >"$work/install.log"
"$cmake" -S "$source" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log"
"$cmake" --build "$work/build" -j2 >"$work/build.log"
"$work/build/consumer"
# The installed Python module, where Debian's python3 looks under the prefix, finds its libraries.
package=$(find "$work/prefix" -path '*/dist-packages/lmk' -type d | head -n 1)
if [ -n "$package" ]; then
  PYTHONPATH=$(dirname "$package") /usr/bin/python3 -c "import lmk; print('python: lmk', lmk.__version__)"
fi
if [ -n "$forbidden" ]; then
  loaded=$(ldd "$work/build/consumer")
  if grep -E "$forbidden" <<<"$loaded"; then
    echo "consumer_test.sh: the consumer loads libraries matching '$forbidden' (above)" >&2
    exit 1
  fi
  echo "consumer_test.sh: nothing matching '$forbidden' among its $(wc -l <<<"$loaded") libraries"
fi
