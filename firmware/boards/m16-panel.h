// Board: the ATmega16 lathe controller of firmware/boards/m16-lathe.h with
// the operator panel (HD44780 on PORTA, 4x4 keypad on PORTB:
// firmware/apps/lathe/operator.h) in place of the UART front end: both do
// not fit the 16 KB with 10 % to spare. Same wiring, same leadscrew.
// avrmotion-board: mcu=atmega16 f_cpu=16000000 app=lathe
#pragma once
#include "m16-lathe.h"

namespace board {

constexpr bool kOperatorPanel = true;

}  // namespace board
