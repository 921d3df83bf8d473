#!/usr/bin/env bash
# Installs dependencies, builds Release and runs acommsd in the foreground on
# the example config, with its data and socket under ./var/. Ctrl-C stops it
# cleanly. In another terminal: build/cli/acommsctl --socket var/vehicle/acommsd.sock status
set -euo pipefail
cd "$(dirname "$0")/.."

bash packaging/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target acommsd acommsctl -j "$(nproc)"
mkdir -p var
exec build/daemon/acommsd --config examples/vehicle.conf
