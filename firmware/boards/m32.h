// Board: ATmega32 printer/CNC controller (seed-002), as the printer: the hot
// end and the G-code machine for Marlin hosts (printcore, OctoPrint, cncjs
// in Marlin mode). The program: firmware/boards/common/m32_printer.h;
// m32-grbl.h is the same printer for grbl hosts.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_printer.h"

namespace board {

// kHeater makes the cnc program link the heater service (firmware/services/,
// firmware/apps/cnc/app.cmake) and take the heater M-codes.
constexpr bool kHeater = true;
constexpr Protocol kProtocol = Protocol::marlin;  // docs/protocol.md
// What a slicer's file needs instead of M303 (firmware/board.h): tune the
// hot end with the m32-grbl image (M303, then M500), whose gains this image
// reads from the EEPROM (docs/heater.md).
constexpr bool kPrinterCodes = true;
constexpr bool kAutotune = false;

}  // namespace board
