#!/usr/bin/env bash
# Installs the Debian 12 packages acommsd builds from (idempotent: does nothing
# when they are all present). With --test, also what the test suite needs.
# Runs apt-get through sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  # gRPC and protobuf, with the static archives (.a) the binaries link in
  libgrpc++-dev libgrpc-dev protobuf-compiler-grpc libprotobuf-dev libprotoc-dev protobuf-compiler
  libabsl-dev libre2-dev libc-ares-dev libssl-dev zlib1g-dev
  libcrypto++-dev libsqlite3-dev
  # header-only
  libspdlog-dev libfmt-dev libasio-dev libcli11-dev
  # PNG output of `acommsctl gram tl --png` (stb_image_write)
  libstb-dev
  # header-only: Eigen, for the position-telemetry Kalman filter (daemon/telemetry)
  libeigen3-dev
  # WGS84 lat/lon <-> local metres for the telemetry datum (static archive)
  libgeographiclib-dev
  # Leaflet, built into acommsctl for the map page of `geov serve` (cli/geov)
  libjs-leaflet
  # DejaVu Sans, built into acommsctl for the text in its PNG pictures (cli/plot)
  fonts-dejavu-core
)
if [[ "${1:-}" == "--test" ]]; then
  # clang and its runtime give libFuzzer with ASan/UBSan for the fuzz targets
  packages+=(libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev)
  # the Python client example and its test (tests/integration/python_client_test.py)
  packages+=(python3-grpcio python3-protobuf)
  # the package test: dpkg-shlibdeps for cpack, systemd-analyze to verify the unit
  packages+=(dpkg-dev systemd)
  # the TLS tests make their CAs and certificates with the openssl command
  packages+=(openssl)
  # the map page in a real headless browser (tests/integration/geov_browser_test.cpp)
  packages+=(chromium chromium-driver)
fi

missing=()
for package in "${packages[@]}"; do
  if [[ "$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null)" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
