#!/usr/bin/env bash
# Builds the Debian package from a built tree and checks it:
#   - the .deb holds exactly the expected files (binaries, unit, conffile,
#     public .proto files, bash completion), owned by root;
#   - its control data: conffiles, maintainer scripts, name, version, Depends;
#   - the maintainer scripts run (with every command they call stubbed);
#   - systemd-analyze verify accepts the unit (skipped if systemd-analyze is
#     not installed);
#   - extracted into a temporary root, acommsd accepts the shipped config and
#     serves with it, and acommsd and acommsctl find the packaged .proto files
#     (dccl/option_extensions.proto) beside themselves with no include flag.
# Nothing is installed on this machine.
#
# Usage: package_test.sh <cpack> <build dir> <source dir> <version>
set -euo pipefail

cpack=$1
build_dir=$2
source_dir=$3
version=$4

work=$(mktemp -d)
daemon_pid=""
cleanup() {
  if [[ -n "$daemon_pid" ]]; then kill "$daemon_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
step() { echo "--- $*"; }

# --- Build the package. cpack installs the tree's current build into a
# --- staging directory under $work: it builds nothing itself.
step "cpack -G DEB"
if ! "$cpack" -G DEB --config "$build_dir/CPackConfig.cmake" -B "$work/out" >"$work/cpack.log" 2>&1; then
  cat "$work/cpack.log"
  fail "cpack failed"
fi
shopt -s nullglob
debs=("$work"/out/*.deb)
shopt -u nullglob
[[ ${#debs[@]} -eq 1 ]] || fail "expected one .deb in $work/out, found ${#debs[@]}"
deb=${debs[0]}
echo "$(basename "$deb"): $(stat -c %s "$deb") bytes"

# --- The files. Directories are left out: only what the package owns counts.
step "dpkg-deb -c"
dpkg-deb -c "$deb" >"$work/listing"
grep -v '^d' "$work/listing" | awk '{print $NF}' | sort >"$work/files"
{
  echo ./etc/acommsd/acommsd.conf
  echo ./lib/systemd/system/acommsd.service
  echo ./usr/bin/acommsctl
  echo ./usr/bin/acommsd
  echo ./usr/share/bash-completion/completions/acommsctl
  (cd "$source_dir/api/proto" && find . -name '*.proto' | sed 's|^\./|./usr/share/acommsd/proto/|')
} | sort >"$work/expected"
grep -qx ./usr/share/acommsd/proto/dccl/option_extensions.proto "$work/expected" ||
  fail "api/proto/dccl/option_extensions.proto is missing from the source tree"
if ! diff -u "$work/expected" "$work/files"; then
  fail "the package's files differ from the expected list (- expected, + in the package)"
fi
if grep -v ' root/root ' "$work/listing"; then fail "entries above are not owned by root/root"; fi
for binary in ./usr/bin/acommsd ./usr/bin/acommsctl; do
  grep -q "^-rwxr-xr-x .* $binary\$" "$work/listing" || fail "$binary is not mode 0755"
done
grep -q '^-rw-r--r-- .* ./etc/acommsd/acommsd.conf$' "$work/listing" || fail "the config is not mode 0644"
sed 's/^/  /' "$work/files"

# --- Control data.
step "dpkg-deb -I / -e"
dpkg-deb -I "$deb" | sed 's/^/  /'
dpkg-deb -e "$deb" "$work/control"
[[ "$(cat "$work/control/conffiles")" == /etc/acommsd/acommsd.conf ]] ||
  fail "conffiles is not exactly /etc/acommsd/acommsd.conf: $(cat "$work/control/conffiles")"
for script in postinst prerm postrm; do
  [[ -x "$work/control/$script" ]] || fail "maintainer script $script is missing or not executable"
  sh -n "$work/control/$script" || fail "$script: shell syntax error"
done
field() { dpkg-deb -f "$deb" "$1"; }
[[ "$(field Package)" == acommsd ]] || fail "Package: $(field Package)"
[[ "$(field Version)" == "$version" ]] || fail "Version: $(field Version), expected $version"
[[ "$(field Section)" == net ]] || fail "Section: $(field Section)"
depends=$(field Depends)
[[ "$depends" == *adduser* ]] || fail "Depends lacks adduser: $depends"
[[ "$depends" == *libc6* ]] || fail "Depends lacks libc6 (dpkg-shlibdeps did not run?): $depends"

# --- The maintainer scripts, with PATH holding only stubs that log their
# --- calls: nothing on this machine changes, and a command the scripts call
# --- without a stub here fails them. (Where systemd runs, /run/systemd/system
# --- exists and the scripts would also call systemctl/deb-systemd-invoke,
# --- which are stubbed as well.)
step "maintainer scripts (stubbed)"
mkdir "$work/stubs"
stub() {
  printf '#!/bin/sh\necho "%s $*" >>"%s"\n%s\n' "$1" "$work/calls" "$2" >"$work/stubs/$1"
  chmod +x "$work/stubs/$1"
}
# A fresh machine: no acommsd user or group yet, dialout present.
# shellcheck disable=SC2016  # $2 is the stub's, expanded when it runs
stub getent 'case "$2" in dialout) exit 0;; *) exit 2;; esac'
stub addgroup 'exit 0'
stub adduser 'exit 0'
stub install 'exit 0'
stub deb-systemd-helper 'exit 0'
stub deb-systemd-invoke 'exit 0'
stub systemctl 'exit 0'
PATH="$work/stubs" /bin/sh -e "$work/control/postinst" configure "" || fail "postinst configure failed"
PATH="$work/stubs" /bin/sh -e "$work/control/prerm" remove || fail "prerm remove failed"
PATH="$work/stubs" /bin/sh -e "$work/control/postrm" remove || fail "postrm remove failed"
sed 's/^/  /' "$work/calls"
grep -q '^addgroup .*--system.* acommsd$' "$work/calls" || fail "postinst did not create group acommsd"
grep -q '^adduser .*--system.*--home /var/lib/acommsd.* acommsd$' "$work/calls" ||
  fail "postinst did not create system user acommsd with home /var/lib/acommsd"
grep -q '^adduser .*--shell /usr/sbin/nologin' "$work/calls" || fail "user acommsd gets a login shell"
grep -q '^adduser .*acommsd dialout$' "$work/calls" || fail "postinst did not add acommsd to dialout"
grep -q '^deb-systemd-helper enable acommsd.service$' "$work/calls" || fail "postinst did not enable the unit"

# --- The package's files, extracted as they would be installed.
root="$work/root"
dpkg-deb -x "$deb" "$root"

step "systemd-analyze verify"
if command -v systemd-analyze >/dev/null 2>&1; then
  # verify wants ExecStart's program to exist: check a copy that runs the
  # extracted one (a --root= tree would also need all of systemd's units).
  mkdir "$work/unit"
  sed "s|^ExecStart=/usr/bin/acommsd |ExecStart=$root/usr/bin/acommsd |" \
    "$root/lib/systemd/system/acommsd.service" >"$work/unit/acommsd.service"
  grep -q "^ExecStart=$root/usr/bin/acommsd " "$work/unit/acommsd.service" ||
    fail "the unit has no ExecStart=/usr/bin/acommsd line"
  verify_rc=0
  systemd-analyze verify "$work/unit/acommsd.service" >"$work/verify.log" 2>&1 || verify_rc=$?
  cat "$work/verify.log"
  [[ $verify_rc -eq 0 ]] || fail "systemd-analyze verify exited $verify_rc"
  # Unknown keys and unparsable values are only warnings, still failures here.
  if grep -q 'acommsd\.service' "$work/verify.log"; then fail "systemd-analyze verify warned about the unit"; fi
  echo "ok"
else
  echo "SKIPPED: systemd-analyze is not installed (Debian package systemd)"
fi

acommsd="$root/usr/bin/acommsd"
acommsctl="$root/usr/bin/acommsctl"
packaged_protos="$root/usr/share/acommsd/proto"

step "acommsd --check-config on the shipped config"
"$acommsd" --version
"$acommsd" --check-config "$root/etc/acommsd/acommsd.conf" || fail "the shipped config does not check"

# A DCCL message importing the option extensions, loaded with no include
# directory: found only through the lookup beside the executable (or the
# build-time ACOMMS_PROTO_DIR, which the broken-copy checks below rule out).
cat >"$work/ping.proto" <<'EOF'
syntax = "proto2";
import "dccl/option_extensions.proto";
package packagetest;
message Ping {
  option (dccl.msg) = { id: 42 max_bytes: 32 codec_version: 4 };
  required int32 depth = 1 [(dccl.field) = { min: 0 max: 6000 }];
}
EOF

step "acommsctl dccl analyze (no -I)"
"$acommsctl" dccl analyze -f "$work/ping.proto" -t packagetest.Ping || fail "acommsctl cannot load a DCCL message"

step "acommsd serves with the shipped config plus that message"
# The shipped config with the message added (its dccl block is commented
# out); store and socket moved into $work by the command-line overrides.
cp "$root/etc/acommsd/acommsd.conf" "$work/acommsd.conf"
echo "dccl { proto_files: \"$work/ping.proto\" }" >>"$work/acommsd.conf"
socket="$work/acommsd.sock"
"$acommsd" --config "$work/acommsd.conf" --data-dir "$work/state" --socket "$socket" \
  >"$work/daemon.log" 2>&1 &
daemon_pid=$!
for _ in $(seq 100); do
  [[ -S "$socket" ]] && break
  kill -0 "$daemon_pid" 2>/dev/null || break
  sleep 0.1
done
if [[ ! -S "$socket" ]]; then
  cat "$work/daemon.log"
  fail "acommsd did not start with the shipped config"
fi
"$acommsctl" --socket "$socket" status || fail "acommsctl status failed against the packaged daemon"
kill -TERM "$daemon_pid"
daemon_rc=0
wait "$daemon_pid" || daemon_rc=$?
daemon_pid=""
[[ $daemon_rc -eq 0 ]] || { cat "$work/daemon.log"; fail "acommsd exited $daemon_rc on SIGTERM"; }

step "a broken packaged option_extensions.proto is the one both binaries read"
# Proves the packaged directory is searched, and before the build-time one.
echo "this is not protobuf" >>"$packaged_protos/dccl/option_extensions.proto"
if "$acommsctl" dccl analyze -f "$work/ping.proto" -t packagetest.Ping >"$work/analyze.log" 2>&1; then
  fail "acommsctl did not read the packaged dccl/option_extensions.proto"
fi
grep -qF "$packaged_protos/dccl/option_extensions.proto" "$work/analyze.log" ||
  { cat "$work/analyze.log"; fail "acommsctl's error does not name the packaged file"; }
daemon_rc=0
timeout 60 "$acommsd" --config "$work/acommsd.conf" --data-dir "$work/state" --socket "$socket" \
  >"$work/daemon.log" 2>&1 || daemon_rc=$?
[[ $daemon_rc -eq 1 ]] || { cat "$work/daemon.log"; fail "acommsd exited $daemon_rc, expected 1"; }
grep -qF "$packaged_protos/dccl/option_extensions.proto" "$work/daemon.log" ||
  { cat "$work/daemon.log"; fail "acommsd's error does not name the packaged file"; }
echo "ok"

echo "PASS: $(basename "$deb")"
