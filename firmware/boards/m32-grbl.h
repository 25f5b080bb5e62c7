// Board: ATmega32 printer/CNC controller (seed-002), as the printer for grbl
// hosts (cncjs in Grbl mode, grbl streamers): the m32 printer's program
// (firmware/boards/common/m32_printer.h) with the grbl line protocol, so
// its answers, the heater's among them, are grbl's (docs/protocol.md,
// docs/heater.md). m32.h is the same printer for Marlin hosts.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_printer.h"

namespace board {

// kHeater makes the cnc program link the heater service (firmware/services/,
// firmware/apps/cnc/app.cmake) and take the heater M-codes.
constexpr bool kHeater = true;
constexpr Protocol kProtocol = Protocol::grbl;  // docs/protocol.md
// G10/G11 firmware retraction, M207/M208 (firmware/board.h): a slicer's
// "use firmware retraction" file prints here.
constexpr bool kFirmwareRetract = true;

}  // namespace board
