// HD44780 character LCD (2 x 16) on a 4-bit bus, written from the datasheet.
//
// Wiring (the board's LcdD4..LcdD7, LcdRs, LcdRw, LcdE; the seed's in
// firmware/boards/common/m16_wiring.h): PA0..PA3 = D4..D7, PA4 RS, PA5 RW,
// PA6 E; PA7 is left alone.
//
// Contract
//   init() brings the controller up by instruction (the datasheet's 4-bit
//   sequence: 0x3, > 4.1 ms, 0x3, > 100 us, 0x3, 0x2, then function set
//   2 lines 5x8, display off, clear, entry mode increment, display on),
//   loads the progress-bar glyphs 1..5 (1..5 columns lit, am::ui::Screen)
//   into the character RAM and leaves the display blank. It waits with
//   delay loops (the controller needs > 40 ms after power-up; on the
//   m16-panel the first screen shows 67 ms after reset, docs/simulator.md),
//   so it runs once at start-up; interrupts may be on or off.
//   poll(screen) does at most one bus operation per call: a busy-flag read
//   and then either one address instruction or one character of a cell the
//   screen marks dirty (the bit is cleared once the character is written).
//   It never waits for the controller and never turns interrupts off: a call
//   is the busy read's two E pulses and at most two more (the pulses' widths
//   are held by a few cycles of delay), and interrupts served meanwhile
//   only stretch a pulse, which the controller tolerates (it has minimum
//   widths, no maximum). Returns true
//   when the display shows the whole screen.
//   Busy flag with a timeout fallback: the driver reads BF (RW high) before
//   each operation and goes on when it reads 0, or when twice the
//   datasheet's execution time has passed since the last instruction
//   whatever it reads (RW not wired, a broken line, no display: the lines'
//   pull-ups read busy), so a display without a working BF is driven by
//   the datasheet's timing.
//
// Why a character per call: the spindle's edge interrupt must keep its
// latency and the main loop its pace; a whole new screen (32 characters,
// an address instruction at the start of each row) reaches the display in
// 34 calls, and only the cells that changed are sent at all.
#pragma once
#include <stdint.h>

#include "../../core/ui/screen.h"

namespace hd44780 {

void init();
bool poll(am::ui::Screen& screen);

}  // namespace hd44780
