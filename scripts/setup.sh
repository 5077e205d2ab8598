#!/usr/bin/env bash
# Set-up for VoroHex on Debian 12: installs every dependency from Debian's packages,
# builds, and installs the FreeCAD workbench. Idempotent: a second run only rebuilds
# what changed.
#
#   VOROHEX_MOD_DIR   where the workbench goes (default ~/.local/share/FreeCAD/Mod/VoroHex)
#   VOROHEX_BUILD_DIR the CMake build folder (default <repo>/build)
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VOROHEX_BUILD_DIR:-$repo/build}"
mod_dir="${VOROHEX_MOD_DIR:-$HOME/.local/share/FreeCAD/Mod/VoroHex}"

packages=(
  # toolchain
  g++ cmake ninja-build pkg-config
  # geometry kernel (the same OCCT 7.6 that FreeCAD loads), linear algebra, JSON, zlib
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libtbb-dev libeigen3-dev nlohmann-json3-dev zlib1g-dev
  # constrained Delaunay triangulation for the all-quad face mesher
  libcgal-dev libgmp-dev libmpfr-dev
  # integer program of the interval assignment (COIN-OR CBC with CLP)
  coinor-libcbc-dev
  # Python module for FreeCAD's interpreter, and tests
  pybind11-dev python3-dev python3-numpy libgtest-dev
  # FreeCAD (App and GUI) and a headless X server for the GUI tests
  freecad-python3 xvfb xauth
  # the baseline the benchmarks compare against (never used for meshing)
  gmsh python3-gmsh
  # CalculiX: the tests solve a VoroHex INP with it (skipped where it is missing)
  calculix-ccx
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing from Debian: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE=/usr/bin/python3 -DCMAKE_INSTALL_PREFIX="$mod_dir"
fi
cmake --build "$build" -j "$(nproc)"
cmake --install "$build" --prefix "$mod_dir" > /dev/null
echo "setup: built $build/vorohex; workbench installed in $mod_dir"
