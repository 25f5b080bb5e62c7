// Board: the ATmega32 printer/CNC controller (seed-002) with an ATmega1284P
// in its socket (the Sanguinololu's and Melzi's chip: the same 40 pins and
// peripherals, 128 KB of flash, 16 KB of RAM, 4 KB of EEPROM). The whole
// machine of docs/protocol.md in one image, where a 32 KB part holds one
// part of it: the hot end with the printer codes and M303, G2/G3, the
// realtime bytes, firmware retraction, the odometer, the settings in the
// EEPROM and both line protocols, Marlin's by default and grbl's by `$200=0`.
// The wiring is the m32's (firmware/boards/common/m32_wiring.h).
// avrmotion-board: mcu=atmega1284p f_cpu=16000000 app=cnc
#pragma once
#include "common/m32_printer_hardware.h"

namespace board {

// kHeater makes the cnc program link the heater service (firmware/services/,
// firmware/apps/cnc/app.cmake) and take the heater M-codes.
constexpr bool kHeater = true;
constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr bool kCommands = true;  // MOVE, POS, WAIT, RELEASE, MODE beside it
constexpr bool kPrinterCodes = true;
constexpr bool kAutotune = true;
constexpr bool kFirmwareRetract = true;
constexpr bool kArcs = true;
constexpr bool kOdometer = true;
constexpr bool kRealtime = true;
constexpr bool kSettings = true;
constexpr bool kPinPolarities = true;  // $3 direction invert mask, $5 limit pins invert
constexpr bool kProtocolSwitch = true;
constexpr Protocol kProtocol = Protocol::marlin;  // $200's default
constexpr uint8_t kPathBlocks = 16;  // look-ahead ring (firmware/engine/path.h), 62 B a block

}  // namespace board
