// The operator panel of the lathe program: the HD44780 screen and the 4x4
// keypad running the threading workflow (core/ui/workflow.h) on the
// leadscrew API (leadscrew.h).
//
// Contract
//   init() after leadscrew::init() and sei() (the settings block is read
//   from the EEPROM, the display brought up: its first screen 67 ms after
//   reset in the simulator): an invalid block
//   (erased, corrupted, another layout) is replaced by the board's machine
//   and the screen says so. The encoder settings go to
//   leadscrew::set_encoder(). poll() from the main loop: one key scan when
//   due (keypad.h), one step of the workflow, one bus operation of the
//   display (hd44780.h); it never waits and never turns interrupts off, so
//   the leadscrew's interrupts keep their latency while the screen changes.
//   Only on a board whose header sets kOperatorPanel (the m16-panel and
//   m32-servo-panel images): the panel and the UART front end do not both
//   fit the ATmega16. On a DC-servo board the settings hold the PID's gains
//   too (core/ui/settings.h), handed to leadscrew::set_gains().
#pragma once

namespace operator_ui {

void init();
void poll();

}  // namespace operator_ui
