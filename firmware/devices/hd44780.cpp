// HD44780 driver: bus cycles, the start-up sequence and the cell-by-cell
// refresh (contract in hd44780.h). Timing from the datasheet (HD44780U,
// VCC 4.5-5.5 V): E pulse >= 230 ns, E cycle >= 500 ns, address set-up
// >= 40 ns, data set-up >= 80 ns, data out valid <= 160 ns after E rises;
// 37 us per instruction at 270 kHz, 1.52 ms for clear and home. The waits
// below take the older HD44780A figures (450 ns, 1000 ns, 360 ns), which
// cover both.
#include "hd44780.h"

#include <util/delay.h>

#include "../../hal/avr/gpio.h"
#include "../board.h"
#include "../engine/clock.h"

namespace hd44780 {
namespace {

using Data = hal::PortBits<board::LcdD4::port>;
using Rs = board::LcdRs;
using Rw = board::LcdRw;
using E = board::LcdE;
constexpr uint8_t kDataMask = 0x0F;
static_assert(board::LcdD4::bit == 0 && board::LcdD7::bit == 3 && board::LcdD7::port == board::LcdD4::port,
              "D4..D7 on bits 0..3 of one port: one write sets a nibble");

// Cycles of at least `ns` nanoseconds.
constexpr uint32_t cycles(uint32_t ns) { return (F_CPU / 1000000UL * ns + 999) / 1000 + 1; }
// Ticks of the time base covering `us` microseconds from any point in a tick.
constexpr uint32_t ticks(uint32_t us) { return (us * (clock::kTickHz / 1000) + 999) / 1000 + 1; }

constexpr uint32_t kShortTicks = ticks(2 * 37);    // twice the execution time
constexpr uint32_t kLongTicks = ticks(2 * 1520);   // clear, home

constexpr uint8_t kClear = 0x01;
constexpr uint8_t kEntryIncrement = 0x06;
constexpr uint8_t kDisplayOff = 0x08;
constexpr uint8_t kDisplayOn = 0x0C;  // no cursor, no blink
constexpr uint8_t kFourBitTwoLines = 0x28;
constexpr uint8_t kSetCgram = 0x40;
constexpr uint8_t kSetDdram = 0x80;
constexpr uint8_t kBusy = 0x80;
constexpr uint8_t kUnknown = 0xFF;  // the address counter is not in the display RAM

uint8_t address_ = kUnknown;  // where the controller's address counter points
uint32_t issued_ = 0;         // clock::now() at the last instruction
uint32_t wait_ = 0;           // its execution time, in ticks (fallback)

void pulse() {
  E::high();
  __builtin_avr_delay_cycles(cycles(450));
  E::low();
  __builtin_avr_delay_cycles(cycles(550));
}

void nibble(uint8_t n) {
  Data::write(kDataMask, n);
  pulse();
}

void write(bool data, uint8_t b) {
  Rs::set(data);
  nibble(b >> 4);
  nibble(b & kDataMask);
  issued_ = clock::now();
  wait_ = (!data && b <= 0x03) ? kLongTicks : kShortTicks;
}

// The busy flag and address counter: D4..D7 as inputs with pull-ups (a
// missing display reads busy, which the timeout turns into timed waits).
uint8_t read_status() {
  Data::input(kDataMask);
  Data::write(kDataMask, kDataMask);
  Rs::low();
  Rw::high();
  E::high();
  __builtin_avr_delay_cycles(cycles(450));
  uint8_t status = uint8_t(Data::read() << 4);
  E::low();
  __builtin_avr_delay_cycles(cycles(550));
  E::high();
  __builtin_avr_delay_cycles(cycles(450));
  status |= Data::read() & kDataMask;
  E::low();
  Rw::low();
  Data::write(kDataMask, 0);
  Data::output(kDataMask);
  __builtin_avr_delay_cycles(cycles(550));
  return status;
}

bool ready() { return (read_status() & kBusy) == 0 || clock::reached(issued_ + wait_); }

// Twice an instruction's execution time (37 us, or 1.52 ms for clear).
void wait_executed(uint16_t instruction_count) {
  while (instruction_count--) _delay_us(2 * 37);
}

// An instruction during init(), by the datasheet's timing (no busy flag yet).
void command_wait(uint8_t b) {
  write(false, b);
  wait_executed(b <= 0x03 ? 1520 / 37 + 1 : 1);
}

}  // namespace

void init() {
  Data::write(kDataMask, 0);
  Data::output(kDataMask);
  Rs::low();
  Rs::output();
  Rw::low();
  Rw::output();
  E::low();
  E::output();
  wait_executed(50000 / 74);  // > 40 ms after power-up
  nibble(0x3);
  wait_executed(5000 / 74);  // > 4.1 ms
  nibble(0x3);
  wait_executed(2);  // > 100 us
  nibble(0x3);
  wait_executed(2);
  nibble(0x2);
  wait_executed(1);
  command_wait(kFourBitTwoLines);
  command_wait(kDisplayOff);
  command_wait(kClear);
  command_wait(kEntryIncrement);
  // Glyph k (1..5): k columns lit from the left, on all 8 rows.
  command_wait(kSetCgram | 8);
  for (uint8_t k = 1; k <= 5; ++k) {
    const uint8_t row_bits = uint8_t(0x1F & ~(0x1F >> k));
    for (uint8_t r = 0; r < 8; ++r) {
      write(true, row_bits);
      wait_executed(1);
    }
  }
  command_wait(kDisplayOn);
  address_ = kUnknown;
}

bool poll(am::ui::Screen& screen) {
  if (screen.dirty == 0) return true;
  if (!ready()) return false;
  uint8_t i = 0;
  for (uint32_t m = screen.dirty; (m & 1) == 0; m >>= 1) ++i;
  const uint8_t address = uint8_t((i >= am::ui::kCols ? 0x40 : 0) | (i % am::ui::kCols));
  if (address != address_) {
    write(false, uint8_t(kSetDdram | address));
    address_ = address;
    return false;
  }
  write(true, uint8_t(screen.cell[i]));
  screen.dirty &= ~(uint32_t(1) << i);
  ++address_;
  return screen.dirty == 0;
}


}  // namespace hd44780
