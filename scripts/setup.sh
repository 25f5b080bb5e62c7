#!/usr/bin/env bash
# Installs the Debian 12 packages avrmotion needs, if any are missing, and
# configures + builds the project in ./build. Sourced-free: both README
# commands call it first. Needs root or sudo only when something is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(gcc-avr avr-libc binutils-avr simavr libsimavr-dev libelf-dev googletest libgtest-dev
          cmake g++ make pkg-config dpkg-dev xz-utils)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >&2
cmake --build build -j"$jobs" >&2  # stdout is for what the commands print
