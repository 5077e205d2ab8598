#!/usr/bin/env bash
# Set up, build, and run every test (GoogleTest, FreeCAD and GUI tests) with ctest.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VOROHEX_BUILD_DIR:-$repo/build}"
bash "$repo/scripts/setup.sh"
ctest --test-dir "$build" --output-on-failure -j 2 "$@"
