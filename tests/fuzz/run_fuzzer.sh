#!/usr/bin/env bash
# run_fuzzer.sh FUZZER SEED_DIR SECONDS
# Runs a libFuzzer target for a bounded time over the checked-in seeds. New
# inputs go to a scratch directory, so the seeds stay as committed. Fails on
# any crash, sanitizer report or leak (libFuzzer exits non-zero and leaves
# the input as crash-*/leak-* in the scratch dir, whose path is printed).
set -euo pipefail
fuzzer=$(realpath "$1") seeds=$(realpath "$2") seconds=$3
if [[ ! -x "$fuzzer" ]]; then
  echo "fuzzer $fuzzer was not built (configure tests with ACOMMS_FUZZ_BINARY_DIR)"; exit 1
fi
scratch=$(mktemp -d /tmp/acomms-fuzz.XXXXXX)
cd "$scratch"
echo "fuzzing $(basename "$fuzzer") for ${seconds}s; artifacts in $scratch"
mkdir corpus
set +e
"$fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
  -artifact_prefix="$scratch/" corpus "$seeds" > fuzz.log 2>&1
status=$?
set -e
tail -n 40 fuzz.log
if [[ $status -eq 0 ]]; then rm -rf "$scratch"; fi
exit "$status"
