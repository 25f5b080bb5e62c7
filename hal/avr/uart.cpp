#include "uart.h"

#include <avr/interrupt.h>
#include <avr/pgmspace.h>

#include "family.h"

namespace hal {
namespace uart {
namespace {

constexpr uint8_t kTxSize = 64;

uint8_t rx_buf[kRxSize];
volatile uint8_t rx_head, rx_tail;  // head written by the ISR, tail by the reader
volatile bool rx_lost;

uint8_t tx_buf[kTxSize];
volatile uint8_t tx_head, tx_tail;  // head written by the writer, tail by the ISR

}  // namespace

void init(uint32_t f_cpu, uint32_t baud) {
  const uint16_t ubrr = uint16_t((f_cpu / 4 / baud - 1) / 2);  // U2X, rounded
  HAL_UBRRH = uint8_t(ubrr >> 8);
  HAL_UBRRL = uint8_t(ubrr);
  HAL_UCSRA = _BV(HAL_U2X);
  HAL_UCSRC = HAL_UCSRC_8N1;
  HAL_UCSRB = _BV(HAL_RXEN) | _BV(HAL_TXEN) | _BV(HAL_RXCIE);
}

void off() { HAL_UCSRB = 0; }

bool available() { return rx_head != rx_tail; }

uint8_t read() {
  const uint8_t c = rx_buf[rx_tail % kRxSize];
  __atomic_signal_fence(__ATOMIC_ACQ_REL);  // read the byte before freeing its slot
  rx_tail = uint8_t(rx_tail + 1);
  return c;
}

bool overrun() {
  if (!rx_lost) return false;
  rx_lost = false;
  return true;
}

void write(uint8_t c) {
  while (uint8_t(tx_head - tx_tail) == kTxSize) {
  }
  tx_buf[tx_head % kTxSize] = c;
  __atomic_signal_fence(__ATOMIC_RELEASE);  // the byte before the index that publishes it
  tx_head = uint8_t(tx_head + 1);
  HAL_UCSRB |= _BV(HAL_UDRIE);
}

void write(const char* s) {
  while (*s) write(uint8_t(*s++));
}

void write_P(const char* s) {
  for (char c; (c = char(pgm_read_byte(s))) != 0; ++s) write(uint8_t(c));
}

void write_u32(uint32_t v) {
  char digits[10];
  uint8_t n = 0;
  do {
    digits[n++] = char('0' + v % 10);
    v /= 10;
  } while (v);
  while (n) write(uint8_t(digits[--n]));
}

void write_i32(int32_t v) {
  if (v < 0) {
    write('-');
    write_u32(uint32_t(-(v + 1)) + 1u);
  } else {
    write_u32(uint32_t(v));
  }
}

}  // namespace uart
}  // namespace hal

// Both UART handlers re-enable interrupts as soon as their own source is
// masked (RXCIE, UDRIE), so the step interrupt waits for at most their
// prologue, about 30 cycles, and never for their whole body: a
// hardware-timed step pulse must end before the next compare match, 107
// cycles later at 150 kHz. The receive handler masks its own interrupt
// because RXC is a level: with a second byte already in the two-byte
// receive buffer (the first taken late) it stays set after the UDR read,
// and an unmasked handler would nest, store the second byte first and swap
// the two (a line's text changed, its checksum's XOR not). The UCSRB
// read-modify-writes cannot lose a bit: every handler puts back the enable
// it cleared before it returns, so any value read outside one is whole.
namespace {
void take(uint8_t status, uint8_t c) {
  using namespace hal::uart;
  if (status & (_BV(HAL_DOR) | _BV(HAL_FE))) rx_lost = true;
#ifdef HAL_UART_REALTIME
  if (take_realtime(c)) return;
#endif
  const uint8_t head = rx_head;
  if (uint8_t(head - rx_tail) == kRxSize) {
    rx_lost = true;
    return;
  }
  rx_buf[head % kRxSize] = c;
  __atomic_signal_fence(__ATOMIC_RELEASE);  // the byte before the index that publishes it
  rx_head = uint8_t(head + 1);
}
}  // namespace

ISR(HAL_UART_RX_VECT) {
  const uint8_t status = HAL_UCSRA;
  const uint8_t c = HAL_UDR;
  HAL_UCSRB &= uint8_t(~_BV(HAL_RXCIE));  // the next byte waits for this one
  sei();
  take(status, c);
  // Stored: a byte already waiting may nest from here on, and the return
  // runs with interrupts on (the step interrupt is not held up by it).
  HAL_UCSRB |= _BV(HAL_RXCIE);
}

ISR(HAL_UART_UDRE_VECT) {
  using namespace hal::uart;
  HAL_UCSRB &= uint8_t(~_BV(HAL_UDRIE));  // UDRE stays set: mask it, then nest
  sei();
  const uint8_t tail = tx_tail;
  if (tail == tx_head) return;
  HAL_UDR = tx_buf[tail % kTxSize];
  tx_tail = uint8_t(tail + 1);
  cli();
  HAL_UCSRB |= _BV(HAL_UDRIE);
}
