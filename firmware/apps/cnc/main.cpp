// avrmotion firmware entry point: brings the board to its safe power-on state
// (coils off, step lines low, drivers disabled, a heater off), greets the host
// and serves the protocol (and a board's heater and homing services) forever. All
// timing-critical work happens in the step interrupt.
#include <avr/interrupt.h>

#include "../../../hal/avr/uart.h"
#include "../../../hal/avr/watchdog.h"
#include "../../board.h"
#include "protocol.h"
#include "reply.h"
#include "realtime.h"
#include "../../engine/clock.h"
#include "../../engine/step_engine.h"
#include "../../services/heater.h"
#include "../../services/homing.h"
#include "../../services/settings.h"

int main() {
  const bool soft_reset = board::kRealtime && hal::watchdog::after_reset();  // its watchdog off
  hal_disable_jtag();
  board::init();
  engine::init();
  if (board::kHeater) heater::init();  // its first reading takes 1.9 ms: before the clock runs
  clock::init();
  hal::uart::init(F_CPU, board::kBaud);
  sei();
  const char* settings_news = board::kSettings ? settings::boot() : nullptr;
  protocol::banner();
  if (settings_news) reply::info_P(settings_news);  // defaults loaded, and why: once, after the banner
  if (board::kRealtime) realtime::boot(soft_reset);
  for (;;) {
    protocol::poll();
    if (board::kRealtime) realtime::poll();
    if (board::kHeater) heater::poll();
    if (board::kHoming) homing::poll();
  }
}
