#!/usr/bin/env bash
# Generates the Python protobuf and gRPC stubs of the acommsd API
# (api/proto/acomms/v1/*.proto and every file they import) into a directory,
# default examples/python/generated (git-ignored).
#
#   examples/python/generate.sh [OUT_DIR]
#
# Needs protoc and grpc_python_plugin (Debian 12: protobuf-compiler,
# protobuf-compiler-grpc). The code protoc 3.21 generates runs with Debian's
# python3-protobuf (3.21, "4.21.x" as Python reports it) and python3-grpcio.
# PROTOC and GRPC_PYTHON_PLUGIN override the tools' paths.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
proto_root="$(cd "$here/../../api/proto" && pwd)"
out="${1:-$here/generated}"
protoc="${PROTOC:-/usr/bin/protoc}"
plugin="${GRPC_PYTHON_PLUGIN:-/usr/bin/grpc_python_plugin}"

for tool in "$protoc" "$plugin"; do
  if [[ ! -x "$tool" ]]; then
    echo "generate.sh: $tool not found (apt-get install protobuf-compiler protobuf-compiler-grpc)" >&2
    exit 1
  fi
done

# The API files and, transitively, what they import from api/proto
# (google/protobuf/* comes with the protobuf runtime and is skipped).
declare -A seen=()
pending=()
for file in "$proto_root"/acomms/v1/*.proto; do
  pending+=("${file#"$proto_root"/}")
done
files=()
while [[ ${#pending[@]} -gt 0 ]]; do
  file="${pending[0]}"
  pending=("${pending[@]:1}")
  [[ -n "${seen[$file]:-}" ]] && continue
  seen[$file]=1
  files+=("$file")
  while read -r imported; do
    if [[ -f "$proto_root/$imported" ]]; then pending+=("$imported"); fi
  done < <(sed -n 's/^[[:space:]]*import[[:space:]]\+\(public[[:space:]]\+\)\?"\([^"]*\)".*/\2/p' \
             "$proto_root/$file")
done

mkdir -p "$out"
"$protoc" -I "$proto_root" \
  --python_out="$out" \
  --grpc_python_out="$out" \
  --plugin=protoc-gen-grpc_python="$plugin" \
  "${files[@]}"
echo "generate.sh: ${#files[@]} files -> $out"
