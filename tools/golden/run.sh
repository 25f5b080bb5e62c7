#!/usr/bin/env bash
# Recomputes the trapezoid generator's golden hashes on the chip: builds
# tools/golden/chip.cpp for an ATmega328P with the firmware's compiler and
# float library, runs it in simavr and prints what it sent on UART0 (one
# hash per fixed block, then the chain's StepRun count and hash), for
# tools/golden/trapezoid_golden.h.
set -euo pipefail
cd "$(dirname "$0")"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
avr-g++ -mmcu=atmega328p -DF_CPU=16000000UL -std=gnu++14 -Os -mcall-prologues -fno-exceptions -fno-rtti \
  -o "$out/golden.elf" chip.cpp -lm
# simavr echoes UART0 in colour, a line's end shown as '.'.
simavr -m atmega328p -f 16000000 "$out/golden.elf" 2>&1 | sed 's/\x1b\[[0-9;]*m//g' | sed -n 's/^\([0-9x][0-9a-fx ]*\)\.$/\1/p'
