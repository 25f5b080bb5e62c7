#!/usr/bin/env bash
# README command 1: set up, build every image, then run a job in the
# simulator (default: examples/demo.txt on the Uno + Motor Shield image).
#
#   ./scripts/demo.sh [BOARD [JOB]]
#
# Prints the JSON report on standard output; progress, and where the outputs
# went, on standard error. Writes, named after the job and the board:
#   build/<job>-<board>.svg   the pictures (position, velocity, acceleration,
#                             step intervals per axis)
#   build/<job>-<board>.vcd   the trace of pins and interrupts (gtkwave FILE)
# where <job> is the job file's name without .txt or .gcode, and the "-<board>" is left
# out when the name already starts with the board ("m32-direct-demo" on m32-direct):
# demo.txt on uno gives build/demo-uno.svg, examples/m32-direct-demo.txt on m32-direct
# build/m32-direct-demo.svg.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
board=${1:-uno}
input=${2:-examples/demo.txt}
job=$(basename "$input")
job=${job%.txt}
job=${job%.gcode}
case "$job" in
  "$board" | "$board"-*) name=$job ;;
  *) name=$job-$board ;;
esac
rm -f "build/$name.svg" "build/$name.vcd"  # never point at an older run's files
rc=0
./build/sim/avrmotion-sim --board "$board" --input "$input" \
  --plot "build/$name.svg" --vcd "build/$name.vcd" --progress || rc=$?
if [ -f "build/$name.svg" ]; then
  echo "pictures: build/$name.svg (open it in a web browser)" >&2
  echo "trace:    build/$name.vcd (gtkwave build/$name.vcd; Debian package gtkwave)" >&2
fi
exit "$rc"
