#!/usr/bin/env bash
# Installs dependencies, builds Release, and runs the example two-node
# network on this machine: a simulated vehicle (modem id 1) and its topside
# (modem id 2), two acommsd processes sharing a simulated acoustic channel
# over loopback with fixed TDMA (examples/vehicle.conf, topside.conf).
# Data and sockets live under ./var/. A small loop stands in for the
# vehicle's autonomy and queues an example.Status every 10 s.
# Ctrl-C stops everything cleanly. The README's walkthrough shows what to
# type in another terminal.
set -euo pipefail
cd "$(dirname "$0")/.."

bash packaging/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target acommsd acommsctl -j "$(nproc)"
mkdir -p var/vehicle var/topside

ctl=build/cli/acommsctl
pids=()
stop() {
  trap - INT TERM EXIT
  kill -TERM "${pids[@]}" 2>/dev/null || true
  wait "${pids[@]}" 2>/dev/null || true
}
trap stop INT TERM EXIT

for node in vehicle topside; do
  build/daemon/acommsd --config "examples/$node.conf" 2> >(sed -u "s/^/[$node] /" >&2) &
  pids+=($!)
done
for node in vehicle topside; do
  until "$ctl" --socket "var/$node/acommsd.sock" status >/dev/null 2>&1; do sleep 0.2; done
done

cat <<'TEXT'

Two nodes are up. In another terminal, from this directory:
  alias vehicle='build/cli/acommsctl --socket var/vehicle/acommsd.sock'
  alias topside='build/cli/acommsctl --socket var/topside/acommsd.sock'
  topside sub example.Status                              # statuses as they arrive
  topside send example.Command dest=1 kind=GOTO x=200 y=-50 depth=30 seq=1
  vehicle sub example.Command                             # the command arriving
  topside queue ls; topside events --since -5m            # and its ACK clearing it
Ctrl-C here stops both nodes.

TEXT

# The vehicle's "autonomy": a status every 10 s, one per vehicle slot.
seq=0
while true; do
  seq=$(( (seq + 1) % 65536 ))
  "$ctl" --socket var/vehicle/acommsd.sock send example.Status \
    dest=2 x=$(( 1500 + seq )) y=0 depth=30 heading=90 speed=1.5 battery=87 mode=SURVEY seq=$seq >/dev/null ||
    echo "[autonomy] status not queued" >&2
  sleep 10
done
