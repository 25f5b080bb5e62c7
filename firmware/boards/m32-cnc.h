// Board: ATmega32 printer/CNC controller (seed-002), as a mill: G2/G3 and
// positions counted mid-move, no heater (the hot end's flash goes to them).
// Wiring: firmware/boards/common/m32_wiring.h.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_wiring.h"

namespace board {

using namespace m32_wiring;

using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all>;

constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr bool kArcs = true;   // G2/G3 as chords (docs/interpolation.md): about 7.5 KB of flash
constexpr uint8_t kPathBlocks = 5;  // look-ahead ring of G-code blocks (firmware/engine/path.h); RAM: 62 B a block, beside a stack of about 450 B (an R arc)

}  // namespace board
