#!/usr/bin/env bash
# Usage: check_daemon_links_no_eval.sh ACOMMSD LIBRARIES
# Fails if acommsd links the offline evaluations (daemon/eval, DESIGN.md:
# "never by acommsd"). Two checks, because a static library on the link line
# adds nothing to the binary until something uses it:
#   * LIBRARIES, the comma-separated targets acommsd links directly or
#     through their link interfaces (configure time), must not hold
#     acomms_eval;
#   * the binary must define no acomms::eval symbol (however it got there).
set -u
binary=$1
libraries=$2
status=0
if [ ! -x "$binary" ]; then
  echo "FAIL: $binary is missing"; exit 1
fi
if [[ ",$libraries," == *",acomms_eval,"* ]]; then
  echo "FAIL: acommsd links acomms_eval; its link closure is:"
  tr ',' '\n' <<< "$libraries" | sed 's/^/  /'
  status=1
fi
if ! symbols=$(nm -C "$binary"); then
  echo "FAIL: nm could not read $binary"; exit 1
fi
if [ -z "$symbols" ]; then
  echo "FAIL: $binary has no symbol table (stripped?): cannot check it"; exit 1
fi
eval_symbols=$(grep -F 'acomms::eval::' <<< "$symbols" | head -n 5)
if [ -n "$eval_symbols" ]; then
  echo "FAIL: $binary defines acomms::eval symbols, e.g.:"
  sed 's/^/  /' <<< "$eval_symbols"
  status=1
fi
# The check itself must be able to see a layer: acommsd has acomms::queue.
if ! grep -qF 'acomms::queue::' <<< "$symbols"; then
  echo "FAIL: no acomms::queue symbol in $binary either: the symbol check sees nothing"
  status=1
fi
[ "$status" -eq 0 ] && echo "ok: acommsd links neither acomms_eval nor any acomms::eval symbol"
exit "$status"
