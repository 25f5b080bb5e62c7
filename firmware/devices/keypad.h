// 4 x 4 matrix keypad (the seed's layout: 1 2 3 A / 4 5 6 B / 7 8 9 C /
// * 0 # D), scanned from the main loop with debounce on the time base.
//
// Wiring (the board's KeypadColumn0.. and KeypadRow0.., the seed's in
// firmware/boards/common/m16_wiring.h): column c (0 = the "1 4 7 *" column) on
// PB(7 - c), row r (0 = the "1 2 3 A" row) on PB(3 - r). Rows are inputs
// with pull-ups; the column being read is driven low and the others are
// inputs with pull-ups, so two keys pressed in one row never short two
// driven outputs.
//
// Contract
//   init() sets the pins. poll() scans all 16 keys when kScanMs have passed
//   since the last scan (a late loop skips scans: never two closer together,
//   or the debounce would count bounces as stable reads) and returns a key's character once per press: when the scan has read the
//   same key (or none) kStableScans times in a row and it differs from the
//   last accepted state; 0 otherwise. Holding a key gives no repeats, a
//   release is not an event, two keys down read as the first in scan order
//   (column by column, top to bottom). Bounce shorter than (kStableScans - 1)
//   x kScanMs = 15 ms never makes an event; a press is accepted 15 to 20 ms
//   after its contact settles.
//   A scan is 4 column selects, each held about 1 us for the rows to
//   settle, with interrupts on.
#pragma once
#include <stdint.h>

namespace keypad {

constexpr uint8_t kScanMs = 5;
constexpr uint8_t kStableScans = 4;

void init();
char poll();

}  // namespace keypad
