// Interrupt-driven UART with ring buffers (8N1).
//
// Contract
//   init() sets the baud rate with U2X (the closest divisor for 16 and 8 MHz
//   parts) and enables the receive interrupt. Received bytes wait in a 64-byte
//   ring; if it fills, further bytes are dropped and overrun() reports it once
//   (as does a hardware data overrun or framing error), so the protocol layer
//   can answer with an error instead of silently losing a line. write() blocks
//   only while the 64-byte transmit ring is full.
#pragma once
#include <stdint.h>

namespace hal {
namespace uart {

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

}  // namespace uart
}  // namespace hal
