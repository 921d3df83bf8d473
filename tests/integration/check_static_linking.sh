#!/usr/bin/env bash
# Fails if ldd shows any library beyond linux-vdso, libc, libm and the loader
# for the given binaries: every third-party library must be linked in.
set -u
allowed='^(linux-vdso\.so\.1|libc\.so\.6|libm\.so\.6|/lib64/ld-linux-x86-64\.so\.2|ld-linux-x86-64\.so\.2|/lib/ld-linux-aarch64\.so\.1|ld-linux-aarch64\.so\.1)$'
status=0
for binary in "$@"; do
  if [ ! -x "$binary" ]; then
    echo "FAIL: $binary is missing"; status=1; continue
  fi
  libs=$(ldd "$binary" | awk '{print $1}')
  echo "$binary:"; echo "$libs" | sed 's/^/  /'
  while read -r lib; do
    [ -z "$lib" ] && continue
    if ! [[ "$lib" =~ $allowed ]]; then
      echo "FAIL: $binary links $lib dynamically"; status=1
    fi
  done <<< "$libs"
done
[ "$status" -eq 0 ] && echo "ok: only the C library family is linked dynamically"
exit "$status"
