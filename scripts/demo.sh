#!/usr/bin/env bash
# README command 1: set up, build every image, then run the demo job in the
# simulator: examples/demo.txt on the Uno + Motor Shield image. Prints the JSON
# report; writes the picture to build/demo.svg.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
board=${1:-uno}
input=${2:-examples/demo.txt}
./build/sim/avrmotion-sim --board "$board" --input "$input" --plot build/demo.svg --progress
echo "picture: build/demo.svg" >&2
