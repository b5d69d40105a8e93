#!/usr/bin/env bash
# Installs the Debian packages the project needs (as root), or prints the exact apt-get line.
# Called by `make -f Makefile.cases demo|test|build`; safe to run again (does nothing when all is there).
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libhdf5-dev libvtk9-dev libcli11-dev libgtest-dev libtomlplusplus-dev
  python3 python3-h5py python3-numpy python3-scipy python3-matplotlib hdf5-tools
  xvfb xauth
)

# `bootstrap.sh fuzz`: also clang, its sanitizer runtimes and its OpenMP for the sanitizer build.
[ "${1:-}" = fuzz ] && packages+=(clang libclang-rt-14-dev libomp-14-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

line="apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "bootstrap: missing Debian packages: ${missing[*]}" >&2
  echo "bootstrap: run as root:  apt-get update && $line" >&2
  exit 1
fi
echo "bootstrap: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# shellcheck disable=SC2086
apt-get install -y --no-install-recommends "${missing[@]}"
