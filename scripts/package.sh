#!/usr/bin/env bash
# Builds the Debian package of VoroHex: set-up and build (scripts/setup.sh), then CPack.
# The .deb lands in <repo>/out/; install it with `sudo apt install ./out/vorohex_*.deb`.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VOROHEX_BUILD_DIR:-$repo/build}"
bash "$repo/scripts/setup.sh"
cpack --config "$build/CPackConfig.cmake" -B "$repo/out"
ls "$repo"/out/vorohex_*.deb
