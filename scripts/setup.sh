#!/usr/bin/env bash
# Install every system package xparam needs (Debian bookworm), then configure and build.
# Idempotent; run as root or with sudo available. Usage: scripts/setup.sh [BUILD_DIR] [extra cmake args...]
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libopenmesh-dev libeigen3-dev libtbb-dev libcli11-dev
  libhdf5-dev hdf5-tools nlohmann-json3-dev libssl-dev
  libgtest-dev googletest libbenchmark-dev
  libcgal-dev
  python3 python3-h5py parallel libxml2-utils bsdutils
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  echo "setup: installing ${missing[*]}" >&2
  "${sudo_cmd[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
shift || true
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build" -j "$(nproc)"
