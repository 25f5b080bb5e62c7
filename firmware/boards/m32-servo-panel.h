// Board: the ATmega16 lathe controller of firmware/boards/m16-servo.h (the
// seed's DC servo on the leadscrew) with an ATmega32 in the ATmega16's
// socket, and the operator panel (HD44780 on PORTA, 4x4 keypad on PORTB:
// firmware/apps/lathe/operator.h) in place of the UART front end, as the
// m16-panel is to the m16-lathe. The settings menu holds the servo's
// encoder, gearbox and PID gains (core/ui/settings.h, in the EEPROM); a
// ratio the follower cannot hold exactly is approximated, its error shown.
//
// Why the ATmega32: the servo, the panel and the gains' conversion take
// 15.6 KB, which fits the ATmega16's 16 KB but not with the 10 % the lathe
// images keep free (docs/lathe.md). The ATmega32 has the ATmega16's pins,
// peripherals and registers in the same 40-pin package, with 32 KB of
// flash, 2 KB of RAM and 1 KB of EEPROM: the same board, the same wiring
// (firmware/boards/common/m16_wiring.h), the same servo.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=lathe
#pragma once
#include "m16-servo.h"

namespace board {

constexpr bool kOperatorPanel = true;
// Room for the approximated ratios (board.h): a pitch the follower cannot
// run exactly is cut at the nearest ratio it can, its error on the screen.
constexpr bool kApproximateRatios = true;

}  // namespace board
