#!/usr/bin/env bash
# Installs the Debian packages subsurf builds and tests with; only the missing
# ones, non-interactively. Safe to run again: it does nothing when all are there.
set -euo pipefail

packages=(
  build-essential cmake pkg-config clang libomp-dev
  libembree-dev libopenexr-dev libstb-dev libcjson-dev libcriterion-dev
  libfftw3-dev libgsl-dev libopenmpi-dev openmpi-bin libplplot-dev zlib1g-dev jq
  libgmsh-dev libsuitesparse-dev
  clang libclang-rt-14-dev libomp-dev lld clang-format clang-tidy
  chromium
  python3-numpy python3-pytest
  libopenvdb-dev libboost-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
if ! $sudo apt-get install -y --no-install-recommends "${missing[@]}" >/dev/null 2>&1; then
  $sudo apt-get update -q >/dev/null
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
