#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# CTest's entry to the browser test: skipped (77) with the reason when Node.js is missing.
set -euo pipefail
if ! command -v node >/dev/null 2>&1; then
  echo "SKIP: Node.js is not installed (scripts/install-deps.sh installs nodejs)"
  exit 77
fi
# Debian's node modules (node-ws) live in /usr/share/nodejs, which not every Node.js searches.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
exec node "$(dirname "$0")/browser_test.js" "$@"
