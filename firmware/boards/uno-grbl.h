// Board: the Uno of firmware/boards/uno.h (Arduino Uno + Adafruit Motor
// Shield v1: the same axes, pins and limits) for grbl senders: grbl's
// realtime bytes (`?` status, `!` feed hold, `~` resume, Ctrl-X soft reset:
// firmware/apps/cnc/realtime.h, docs/protocol.md) in place of the direct
// controls (MOVE, POS, WAIT, RELEASE, MODE). Both do not fit the Uno's
// 31.5 KB beside the G-code machine; M350 still sets the shield's
// excitation modes from G-code.
// avrmotion-board: mcu=atmega328p f_cpu=16000000 app=cnc
#pragma once
#include "uno.h"

namespace board {

constexpr bool kRealtime = true;
constexpr bool kCommands = false;

}  // namespace board
