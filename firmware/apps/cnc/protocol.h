// The line protocol on the UART (docs/protocol.md), in the board's style
// (board::kProtocol; with board::kProtocolSwitch the style in force, the
// setting $200: reply::marlin()): grbl 1.1 (`ok`, `error:N`) or Marlin
// (`ok`, numbered and checksummed lines, `Resend:`). One answer per line.
//
// Contract
//   banner() once after reset; poll() from the main loop. poll() reads
//   received bytes into the line buffer only while no line is waiting, so a
//   line that must wait (a move while the ring is full, POS/WAIT/RELEASE or
//   M400 until motion ends) holds back the next one instead of losing it.
//   A sender keeps one line in flight, or counts characters against
//   kReceiveRing (grbl's streaming).
#pragma once
#include <stdint.h>

#include "../../../hal/avr/uart.h"

namespace protocol {

constexpr uint8_t kLineCapacity = 96;  // Marlin's MAX_CMD_SIZE; a longer line is refused whole
// The UART's receive ring (hal::uart::kRxSize: 128 with grbl's realtime
// bytes, 64 otherwise), which `$I` reports to a character-counting sender
// (tests/sim/test_styles.cpp checks it against the ring in the image).
constexpr uint8_t kReceiveRing = hal::uart::kRxSize;

void banner();
void poll();

}  // namespace protocol
