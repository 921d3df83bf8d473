#!/usr/bin/env bash
# Installs dependencies, builds everything (Release, with tests) and runs the
# whole test suite with ctest. This is what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."

bash packaging/install-deps.sh --test
jobs=$(nproc)
# The fuzz targets are built by clang with sanitizers in a tree of their own;
# the main tree runs them, time-bounded, as ctest tests (fuzz.*).
CC=clang CXX=clang++ cmake -S . -B build/fuzz -DACOMMS_BUILD_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build/fuzz -j "$jobs"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DACOMMS_BUILD_TESTS=ON \
  -DACOMMS_FUZZ_BINARY_DIR="$PWD/build/fuzz" >/dev/null
cmake --build build -j "$jobs"
cd build
ctest --output-on-failure -j "$jobs" --timeout 600
