// Prints the trapezoid generator's golden hashes as the chip computes them
// (tools/golden/trapezoid_golden.h): one line per fixed block, then the
// chain's StepRun count and hash, on UART0 at 115200 baud, then sleeps.
// Built and run by tools/golden/run.sh (ATmega328P in simavr).
#include <avr/io.h>
#include <avr/sleep.h>

#include "trapezoid_golden.h"

namespace {

void put(char c) {
  while (!(UCSR0A & _BV(UDRE0))) {
  }
  UDR0 = uint8_t(c);
}

void put_hex(uint32_t v) {
  put('0');
  put('x');
  for (int8_t shift = 28; shift >= 0; shift -= 4) put("0123456789abcdef"[(v >> shift) & 15]);
}

void put_dec(uint32_t v) {
  char d[10];
  uint8_t n = 0;
  do {
    d[n++] = char('0' + v % 10);
    v /= 10;
  } while (v);
  while (n) put(d[--n]);
}

}  // namespace

int main() {
  UBRR0 = 16;  // 115200 at 16 MHz with U2X
  UCSR0A = _BV(U2X0);
  UCSR0B = _BV(TXEN0);
  for (const am::golden::Block& g : am::golden::kBlocks) {
    put_hex(am::golden::hash_block(g.b, g.tick_hz));
    put('\n');
  }
  const am::golden::ChainHash c = am::golden::hash_chain();
  put_dec(c.step_runs);
  put(' ');
  put_hex(c.hash);
  put('\n');
  sleep_mode();  // simavr ends the run when the CPU sleeps with interrupts off
}
