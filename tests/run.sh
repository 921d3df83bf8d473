#!/usr/bin/env bash
# Installs dependencies, builds everything (Release, with tests) and runs the
# whole test suite with ctest. This is what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."

bash packaging/install-deps.sh --test
jobs=$(nproc)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DACOMMS_BUILD_TESTS=ON >/dev/null
cmake --build build -j "$jobs"
cd build
ctest --output-on-failure -j "$jobs" --timeout 600
