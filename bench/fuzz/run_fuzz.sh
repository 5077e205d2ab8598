#!/usr/bin/env bash
# Fuzzes the mesh readers of `vorohex check` and the shape readers (STEP/BREP/IGES) with
# libFuzzer for a bounded time each, then writes bench/results/fuzz.md. Not part of CI.
#
#   bench/fuzz/run_fuzz.sh [SECONDS]     seconds per target (default 600)
#
#   VOROHEX_FUZZ_BUILD   build folder (default <repo>/build-fuzz; working corpora, logs and
#                        findings go to its work/ subfolder)
#   VOROHEX_FUZZ_JOBS    parallel compile jobs (default: all cores)
#   VOROHEX_FUZZ_INSTALL=1  install missing Debian packages (clang, libclang-rt-14-dev)
#
# The targets run one after the other (one core). Inputs in bench/fuzz/regressions/ are
# replayed first and must not crash. A target that stops at a finding goes on in a new
# segment with the same working corpus until its time is used up (fuzz_report.py).
set -euo pipefail

seconds="${1:-600}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
build="${VOROHEX_FUZZ_BUILD:-$repo/build-fuzz}"
work="$build/work"
targets=(fuzz_mesh_reader fuzz_shape_reader)

# --- Prerequisites: clang with libFuzzer and the sanitizer runtimes (Debian packages) ----
packages=(clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "${VOROHEX_FUZZ_INSTALL:-0}" = 1 ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
  else
    echo "run_fuzz: missing Debian packages: ${missing[*]}" >&2
    echo "  install them with: sudo apt-get install ${missing[*]}" >&2
    echo "  (or run with VOROHEX_FUZZ_INSTALL=1; the rest comes from scripts/setup.sh)" >&2
    exit 2
  fi
fi
probe="$(mktemp -d)"
trap 'rm -rf "$probe"' EXIT
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' \
  > "$probe/probe.cpp"
if ! clang++ -fsanitize=fuzzer,address,undefined "$probe/probe.cpp" -o "$probe/probe" 2> "$probe/err"; then
  echo "run_fuzz: clang++ cannot build a libFuzzer target:" >&2
  cat "$probe/err" >&2
  echo "  (Debian: sudo apt-get install clang libclang-rt-14-dev)" >&2
  exit 2
fi

# --- Build (idempotent) -----------------------------------------------------------------
CC=clang CXX=clang++ cmake -S "$repo" -B "$build" -G Ninja -DVOROHEX_FUZZ=ON \
  -DVOROHEX_BUILD_TESTS=OFF -DVOROHEX_BUILD_PYTHON=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build "$build" --target "${targets[@]}" -j "${VOROHEX_FUZZ_JOBS:-$(nproc)}"

export LSAN_OPTIONS="suppressions=$here/lsan_occt.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# -close_fd_mask=1: OCCT's readers print to stdout; libFuzzer reports on stderr.
flags=(-rss_limit_mb=4096 -timeout=60 -print_final_stats=1 -close_fd_mask=1)

# --- Regressions: every kept input must run without a finding ----------------------------
replayed=0
for t in "${targets[@]}"; do
  inputs=("$here/regressions/$t"/*)
  [ -e "${inputs[0]}" ] || continue
  if ! "$build/fuzz/$t" "${flags[@]}" "${inputs[@]}" > "$probe/replay.log" 2>&1; then
    echo "run_fuzz: a regression input of $t fails again:" >&2
    grep -E "ERROR|Running:" "$probe/replay.log" | tail -5 >&2
    exit 1
  fi
  replayed=$((replayed + ${#inputs[@]}))
done
echo "run_fuzz: replayed $replayed regression inputs, no finding"

# --- Fuzz each target on a working copy of its seed corpus --------------------------------
for t in "${targets[@]}"; do
  dir="$work/$t"
  rm -rf "$dir"
  mkdir -p "$dir/corpus" "$dir/artifacts" "$dir/logs"
  cp "$here/corpus/$t/"* "$dir/corpus/"
  : > "$dir/segments"
  left="$seconds"
  segment=0
  echo "run_fuzz: $t for ${seconds}s"
  while [ "$left" -gt 0 ] && [ "$segment" -lt 1000 ]; do
    segment=$((segment + 1))
    log="$(printf '%s/logs/seg%03d.log' "$dir" "$segment")"
    start="$(date +%s)"
    set +e
    "$build/fuzz/$t" "${flags[@]}" -max_total_time="$left" -artifact_prefix="$dir/artifacts/" \
      "$dir/corpus" > "$log" 2>&1
    rc=$?
    set -e
    used=$(($(date +%s) - start))
    echo "$segment $rc $used" >> "$dir/segments"
    left=$((left - used))
    [ "$rc" -eq 0 ] && break
    echo "  segment $segment stopped after ${used}s: $(grep -o -m1 'Test unit written to .*' "$log" || echo "exit $rc")"
  done
done

python3 "$here/fuzz_report.py" --root "$repo" --build "$build" --work "$work" \
  --out "$repo/bench/results/fuzz.md" \
  --budget "$seconds" --replayed "$replayed" --flags "${flags[*]}" "${targets[@]}"
echo "run_fuzz: wrote bench/results/fuzz.md"
