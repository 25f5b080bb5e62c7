// Interrupt-driven UART with ring buffers (8N1).
//
// Contract
//   init() sets the baud rate with U2X (the closest divisor for 16 and 8 MHz
//   parts) and enables the receive interrupt. Received bytes wait in a ring
//   of HAL_UART_RX_SIZE bytes (64, or 128 where the program sets it: grbl's
//   senders keep up to 128 bytes in flight); if it fills,
//   further bytes are dropped and overrun() reports it once
//   (as does a hardware data overrun or framing error), so the protocol layer
//   can answer with an error instead of silently losing a line. write() blocks
//   only while the 64-byte transmit ring is full.
//   With HAL_UART_REALTIME defined, take_realtime(c), which the program
//   defines, sees every received byte first, in the receive interrupt with
//   interrupts enabled: it takes the program's realtime commands out of the
//   stream there, even mid-line and with the ring full.
#pragma once
#include <stdint.h>

// The program sets the receive ring's size (a power of two up to 128): 128
// where grbl's senders count characters against it, 64 otherwise.
#ifndef HAL_UART_RX_SIZE
#define HAL_UART_RX_SIZE 64
#endif

namespace hal {
namespace uart {

constexpr uint8_t kRxSize = HAL_UART_RX_SIZE;
static_assert(kRxSize <= 128 && (kRxSize & (kRxSize - 1)) == 0, "HAL_UART_RX_SIZE: a power of two up to 128");

void init(uint32_t f_cpu, uint32_t baud);
void off();              // receiver and transmitter off: RXD/TXD are plain pins
bool available();
uint8_t read();          // valid only when available()
bool overrun();          // true once after bytes were lost; clears the flag
void write(uint8_t c);
void write(const char* s);
void write_P(const char* progmem_s);
void write_u32(uint32_t v);
void write_i32(int32_t v);
bool take_realtime(uint8_t c);  // true: c is consumed, not queued

}  // namespace uart
}  // namespace hal
