#!/usr/bin/env bash
# README command 2: set up, build, run every test (host core tests, simavr
# tests on the real images, simulator calibration).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cd build
ctest --output-on-failure -j"$(nproc 2>/dev/null || echo 2)"
