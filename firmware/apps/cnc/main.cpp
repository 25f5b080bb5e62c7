// avrmotion firmware entry point: brings the board to its safe power-on state
// (coils off, step lines low, drivers disabled), greets the host and serves the
// protocol forever. All timing-critical work happens in the step interrupt.
#include <avr/interrupt.h>

#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "protocol.h"
#include "../../engine/clock.h"
#include "../../engine/step_engine.h"

int main() {
  hal_disable_jtag();
  board::init();
  engine::init();
  clock::init();
  hal::uart::init(F_CPU, board::kBaud);
  sei();
  protocol::banner();
  for (;;) protocol::poll();
}
