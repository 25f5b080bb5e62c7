// Board: ATmega32 printer/CNC controller (seed-002), as a grbl-style mill
// for cncjs and UGS: G2/G3, positions counted mid-move, the realtime bytes
// (? ! ~ Ctrl-X, docs/realtime.md); no heater and no direct controls (their
// flash goes to the rest; the m32-direct image has them).
// Wiring: firmware/boards/common/m32_wiring.h.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_wiring.h"

namespace board {

using namespace m32_wiring;

using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all>;

constexpr bool kRealtime = true;   // firmware/apps/cnc/realtime.h
constexpr bool kCommands = false;  // G-code only
// No settings in the EEPROM (kSettings, firmware/services/settings.h): they
// need about 2.8 KB of flash, this image has 0.2 KB left (docs/settings.md).
constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr bool kArcs = true;   // G2/G3 as chords (docs/interpolation.md): about 7.5 KB of flash
// The look-ahead ring (firmware/engine/path.h), 62 B a block: four blocks
// are too short to keep a 10 mm circle at 20 mm/s, and five leave an R
// arc's stack (470 B, tests/sim/test_arcs.cpp) 7 bytes short of the data.
constexpr uint8_t kPathBlocks = 5;

}  // namespace board
