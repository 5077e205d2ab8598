#!/usr/bin/env bash
# The main job: set up, mesh the bundled tapered brick, print the quality report and
# write out/tapered_brick.vtu (open it in ParaView).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VOROHEX_BUILD_DIR:-$repo/build}"
bash "$repo/scripts/setup.sh"
mkdir -p "$repo/out"
"$build/vorohex" mesh "$repo/examples/tapered_brick.step" -o "$repo/out/tapered_brick.vtu" \
  --size 0.25 --report "$repo/out/tapered_brick.json"
