#!/usr/bin/env bash
# Installs the Debian 12 packages avrmotion needs, if any are missing, and
# configures + builds the project in ./build. Sourced-free: both README
# commands call it first. Needs root or sudo only when something is missing.
# Everything it prints goes to standard error: standard output is for what
# the README commands themselves print (the demo's JSON report).
set -euo pipefail
cd "$(dirname "$0")/.."

# README.md lists exactly these (tests/sim/test_setup_docs.cpp checks it).
# printrun-common is for the tests only: printrun's printcore, the printer
# host tests/sim/test_printcore.cpp drives the simulated printer with.
packages=(gcc-avr avr-libc binutils-avr simavr libsimavr-dev libelf-dev googletest libgtest-dev
          cmake g++ make pkg-config dpkg-dev xz-utils printrun-common)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${#missing[@]} missing package(s): ${missing[*]}" >&2
  echo "setup: apt-get adds what they depend on and lists it below, then shows each download and unpack" >&2
  echo "setup: apt-get update" >&2
  $sudo apt-get update >&2
  echo "setup: apt-get install ${missing[*]}" >&2
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}" >&2
  echo "setup: packages installed" >&2
fi

jobs=$(nproc 2>/dev/null || echo 2)
echo "setup: configuring and building in build/ ($jobs jobs)" >&2
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >&2
cmake --build build -j"$jobs" >&2
