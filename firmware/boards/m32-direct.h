// Board: ATmega32 printer/CNC controller (seed-002) with the direct controls:
// MOVE, POS, WAIT, RELEASE, MODE (docs/protocol.md) beside G-code, grbl
// style by default (Marlin's by the setting $200=1), no arcs, no realtime
// bytes; the printer's endstops and homing. The image for bringing up motors
// and drivers (a move in steps at a rate and an acceleration of its own) and the
// one the step engine's figures are measured on (docs/benchmarks.md,
// tests/sim/test_invariants.cpp). Wiring: firmware/boards/common/m32_wiring.h.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_wiring.h"

namespace board {

using namespace m32_wiring;

// The printer's endstops and homing (m32_wiring.h, docs/homing.md).
using Endstops = EndstopWiring;
constexpr bool kHoming = true;
constexpr HomingSettings<3> kHomingSettings = printer_homing<Axes>();

using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all, Endstops::claims>;

// Steps/mm, rates, accelerations, junction deviation (and homing and soft
// limits where the board has endstops) in the EEPROM: `$$`, `$N=value`
// (firmware/services/settings.h, docs/settings.md).
constexpr bool kSettings = true;
// grbl's and Marlin's line protocol both, chosen by `$200` (0 grbl, the
// default; 1 Marlin) at run time, with Marlin's settings codes M92 M201
// M203 M205 M500..M503 (docs/protocol.md, docs/settings.md).
constexpr bool kProtocolSwitch = true;
constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr bool kArcs = false;
constexpr uint8_t kPathBlocks = 5;  // look-ahead ring (firmware/engine/path.h), 62 B a block

}  // namespace board
