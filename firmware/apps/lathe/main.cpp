// The lathe program's entry point: the board's safe power-on state (driver
// disabled, step low, the L298 off), the time base, the leadscrew and the
// UART front end, or on a board with kOperatorPanel the operator panel
// (operator.h) in its place; the main loop polls them. Everything that must keep step
// with the spindle runs in the leadscrew's interrupts, so the loop's own
// work (the front end's replies, an operator panel's screen) never disturbs
// the following.
#include <avr/interrupt.h>

#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "../../engine/clock.h"
#include "leadscrew.h"
#include "operator.h"
#include "protocol.h"

int main() {
  hal_disable_jtag();
  board::init();
  clock::init();
  leadscrew::init();
  if (!board::kOperatorPanel) hal::uart::init(F_CPU, board::kBaud);
  sei();
  if (board::kOperatorPanel) operator_ui::init();
  else protocol::banner();
  for (;;) {
    leadscrew::poll();
    if (board::kOperatorPanel) operator_ui::poll();
    else protocol::poll();
  }
}
