#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds oneTBB with ThreadSanitizer, from Debian's source of the version installed (libtbb-dev),
# for `scripts/test.sh --tsan`. Debian's libtbb is not instrumented: ThreadSanitizer would not see
# its task hand-offs, and every parallel loop would report races that are not there. Loaded in its
# place (LD_LIBRARY_PATH; same version, same ABI), the instrumented library makes them visible.
#
#   bash scripts/build-tbb-tsan.sh PREFIX    installs PREFIX/lib/libtbb.so.12 (about 30 s; kept)
set -euo pipefail
prefix=${1:?usage: build-tbb-tsan.sh PREFIX}
version=$(dpkg-query -W -f '${Version}' libtbb-dev)  # e.g. 2021.8.0-2+deb12u1
upstream=${version%%-*}
if [ -f "$prefix/lib/libtbb.so.12" ] && [ "$(cat "$prefix/DEBIAN_VERSION" 2>/dev/null)" = "$version" ]; then
  exit 0
fi
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "build-tbb-tsan.sh: oneTBB $upstream (Debian $version) with ThreadSanitizer into $prefix"
curl -sSfL -o "$work/onetbb.tar.xz" "$mirror/pool/main/o/onetbb/onetbb_${upstream}.orig.tar.xz"
tar xf "$work/onetbb.tar.xz" -C "$work"
# The library only: no tests, no allocator (lmk does not use tbbmalloc).
cmake -S "$work/oneTBB-$upstream" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DTBB_SANITIZE=thread \
  -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF -DCMAKE_INSTALL_PREFIX="$prefix" \
  >"$work/configure.log"
cmake --build "$work/build" -j2 >"$work/build.log"
cmake --install "$work/build" >"$work/install.log"
echo "$version" >"$prefix/DEBIAN_VERSION"
