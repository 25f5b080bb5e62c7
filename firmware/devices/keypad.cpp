// Keypad scan and debounce (contract in keypad.h).
#include "keypad.h"

#include <avr/pgmspace.h>

#include "../../hal/avr/gpio.h"
#include "../board.h"
#include "../engine/clock.h"

namespace keypad {
namespace {

using Port = hal::PortBits<board::KeypadRow0::port>;
constexpr uint8_t kColumns = 0xF0;  // PB7..PB4
constexpr uint8_t kRows = 0x0F;     // PB3..PB0
static_assert(board::KeypadColumn0::bit == 7 && board::KeypadColumn3::bit == 4 && board::KeypadRow0::bit == 3 &&
                  board::KeypadRow3::bit == 0 && board::KeypadColumn0::port == board::KeypadRow0::port,
              "the scan assumes columns PB7..PB4 and rows PB3..PB0 of one port");
constexpr uint8_t kNone = 0xFF;

const char kKeys[16] PROGMEM = {'1', '2', '3', 'A', '4', '5', '6', 'B', '7', '8', '9', 'C', '*', '0', '#', 'D'};

uint32_t next_scan_ = 0;
uint8_t candidate_ = kNone;  // what the last scans read
uint8_t seen_ = 0;           // how many in a row
uint8_t accepted_ = kNone;   // the debounced state

// Key index r * 4 + c of the first key down, or kNone.
uint8_t scan() {
  uint8_t found = kNone, c = 0;
  for (uint8_t column = 0x80; column & kColumns; column = uint8_t(column >> 1), ++c) {
    Port::write(column, 0);  // pull-up off first, then drive low: never high
    Port::output(column);
    __builtin_avr_delay_cycles(F_CPU / 1000000UL);  // ~1 us for the row to settle
    const uint8_t down = uint8_t(~Port::read());
    Port::input(column);     // float first, then pull up
    Port::write(column, column);
    for (uint8_t r = 0; r < 4; ++r)
      if (found == kNone && (down & (0x08 >> r))) found = uint8_t(r * 4 + c);
  }
  return found;
}

}  // namespace

void init() {
  Port::input(kColumns | kRows);
  Port::write(kColumns | kRows, kColumns | kRows);
  next_scan_ = clock::now();
}

char poll() {
  if (!clock::reached(next_scan_)) return 0;
  next_scan_ = clock::now() + clock::ms(kScanMs);  // a late loop skips scans, never bunches them
  const uint8_t key = scan();
  if (key != candidate_) {
    candidate_ = key;
    seen_ = 1;
    return 0;
  }
  if (seen_ < kStableScans) ++seen_;
  if (seen_ < kStableScans || key == accepted_) return 0;
  accepted_ = key;
  return key == kNone ? 0 : char(pgm_read_byte(&kKeys[key]));
}

}  // namespace keypad
