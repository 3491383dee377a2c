#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates lmk's shipped confidence calibration, search/confidence/data/confidence_calibration.json, from
# its data (docs/evaluation.md, "A confidence that transfers"): fitted on the presets paper and
# viewpoints and on the real desk sequence (the sequence tuned on), reported on the occlusion
# preset and the real kitchen sequence (never fitted on).
#   scripts/fit-confidence.sh [WORK_DIR]
# Needs a built lmk ($LMK, default build/tools/lmk) and the shared data ($LMK_SHARED_DATA, default
# ../shared/data). The presets are generated into lmk's cache; the sequences into WORK_DIR (a
# temporary directory by default). About 4 minutes on 2 cores from a clean cache.
set -euo pipefail
cd "$(dirname "$0")/.."
lmk=${LMK:-build/tools/lmk}
data=${LMK_SHARED_DATA:-../shared/data}
work=${1:-$(mktemp -d)}
if [ ! -d "$data/real/desk" ] || [ ! -d "$data/real/redkitchen" ]; then
  echo "fit-confidence: $data/real/desk and redkitchen are needed (set LMK_SHARED_DATA)" >&2
  exit 2
fi
[ -d "$work/desk" ] || "$lmk" gen "$work/desk" --from-rgbd "$data/real/desk" --registered-colour
[ -d "$work/redkitchen" ] || "$lmk" gen "$work/redkitchen" --from-rgbd "$data/real/redkitchen"
"$lmk" calibrate-confidence paper viewpoints "$work/desk" --check occlusion "$work/redkitchen" \
  --features local_margin elsewhere_margin coverage \
  --note "the presets paper and viewpoints (generator defaults) and the real desk sequence (lmk gen --from-rgbd desk --registered-colour); checked on the real kitchen sequence and the occlusion preset, not fitted on" \
  -o search/confidence/data/confidence_calibration.json
