// Board: the m32 printer (firmware/boards/m32.h, Marlin hosts) with a
// common i3-style machine's mechanics in place of the seed's 1 um a step:
// 80 steps/mm on X and Y (a 20-tooth GT2 pulley at 16 microsteps), 400 on Z
// (an 8 mm lead screw), 93 on E (a direct-drive extruder), accelerations
// of 1000 mm/s^2 on X and Y (the board's figure in steps: 200 on Z, 860 on
// E) until a file's M201/M204 says otherwise. The same wiring, hot end,
// endstops, program and flash as the m32; the simulator's printer profile
// (`avrmotion-sim --board m32-i3`, docs/simulator.md).
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_wiring.h"

namespace board {

using Axes = m32_wiring::AxesAt<80000, 400000, 93000>;
constexpr uint32_t kDefaultAccel = 80000;  // steps/s^2
// The top step rate (40 kHz) is the engine's: 500 mm/s on X and Y, 100 on
// Z, 430 on E, above what an i3 runs; a file's M203 holds it lower.

}  // namespace board

#include "common/m32_printer.h"

namespace board {

constexpr bool kHeater = true;  // firmware/apps/cnc/app.cmake reads this line
constexpr Protocol kProtocol = Protocol::marlin;
constexpr bool kPrinterCodes = true;  // as the m32 (firmware/board.h)
constexpr bool kAutotune = false;

}  // namespace board
