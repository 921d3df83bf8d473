#!/usr/bin/env bash
# Installs dependencies, builds everything (Release, with tests) and runs the
# whole test suite with ctest. This is what CI runs (.ci/run). Each build
# phase's wall time is printed before the tests (ctest ends with its own):
# CI's budget is read from these lines.
set -euo pipefail
cd "$(dirname "$0")/.."

phase_start=$SECONDS
timings=()
phase_done() {
  timings+=("$(printf '%-34s %4d s' "$1" $((SECONDS - phase_start)))")
  phase_start=$SECONDS
}

bash packaging/install-deps.sh --test
phase_done "install-deps"
jobs=$(nproc)
# The fuzz targets are built by clang with sanitizers in a tree of their own;
# the main tree runs them, time-bounded, as ctest tests (fuzz.*).
CC=clang CXX=clang++ cmake -S . -B build/fuzz -DACOMMS_BUILD_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build/fuzz -j "$jobs"
phase_done "build: fuzz tree (clang, sanitizers)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DACOMMS_BUILD_TESTS=ON \
  -DACOMMS_FUZZ_BINARY_DIR="$PWD/build/fuzz" >/dev/null
cmake --build build -j "$jobs"
phase_done "build: main tree"
echo "run.sh phases so far:"
printf '  %s\n' "${timings[@]}"
cd build
ctest --output-on-failure -j "$jobs" --timeout 600
