// The ATmega32 board as a printer (seed-002): the hot end, the endstops and
// homing, G-code only. Shared by the two printer images, which differ in the
// line protocol their hosts speak: firmware/boards/m32.h (Marlin: printcore,
// OctoPrint) and firmware/boards/m32-grbl.h (grbl: cncjs in Grbl mode).
// Wiring: m32_wiring.h. Its declarations go straight into namespace board
// (a board's own names win over firmware/board.h's defaults only there);
// each board header adds its kProtocol and still says
// `constexpr bool kHeater = true;` itself (firmware/apps/cnc/app.cmake reads
// that line to link the heater service).
#pragma once
#include "m32_printer_hardware.h"

namespace board {

constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
// A printer host sends G-code only: the flash of the direct controls (MOVE,
// POS, WAIT, RELEASE, MODE) holds the protocol and the heater instead; the
// m32-direct image of this board keeps them.
constexpr bool kCommands = false;
// The flash the heater needs: G2/G3 (7.5 KB) and the odometer (1 KB) are
// in the m32-cnc image of this board instead; M114 counts where the queued
// motion ends.
constexpr bool kArcs = false;
constexpr bool kOdometer = false;
constexpr uint8_t kPathBlocks = 5;  // look-ahead ring of G-code blocks (firmware/engine/path.h); RAM: the heater takes a block's, the stack needs 350 B

}  // namespace board
