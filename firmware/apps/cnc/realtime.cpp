#include "realtime.h"

#include <avr/pgmspace.h>

#include "../../../core/text/fixed_number.h"
#include "../../../hal/avr/step_timer.h"
#include "../../../hal/avr/uart.h"
#include "../../../hal/avr/watchdog.h"
#include "../../board.h"
#include "../../engine/limits.h"
#include "../../engine/path.h"
#include "../../engine/planner.h"
#include "../../engine/step_engine.h"
#include "gcode.h"
#include "reply.h"

namespace realtime {
namespace {

constexpr uint8_t kStatus = 1, kHold = 2, kResume = 4;
volatile uint8_t asked;

// Set by a soft reset that stopped steps, read after the restart: RAM the
// startup code does not clear.
constexpr uint8_t kMotionLost = 0xA5;
uint8_t reset_in_motion __attribute__((section(".noinit")));

// Whether every axis counts in micrometres (a step/dir axis of 1 um per
// step): the report then prints the count as it is.
template <typename Set>
struct InMicrometres;
template <typename... A>
struct InMicrometres<AxisSet<A...>> {
  static constexpr bool all(bool first = true) { return first; }
  template <typename... More>
  static constexpr bool all(bool first, bool second, More... more) {
    return first && all(second, more...);
  }
  static constexpr bool value = all((uint64_t(A::descriptor().steps_per_m) * OwnUnits<A>::per_full_step == 1000000u)...);
};

void write_state() {
  switch (path::hold_state()) {
    case path::Hold::stopping: hal::uart::write_P(PSTR("Hold:1")); return;
    case path::Hold::held: hal::uart::write_P(PSTR("Hold:0")); return;
    default: hal::uart::write_P(limits::alarm() ? PSTR("Alarm") : path::busy() ? PSTR("Run") : PSTR("Idle")); return;
  }
}

[[gnu::noinline]] void report() {
  int32_t now[board::Axes::count];
  planner::positions_now(now);
  hal::uart::write('<');
  write_state();
  hal::uart::write_P(PSTR("|MPos:"));
  char buf[14];
  for (uint8_t i = 0; i < board::Axes::count; ++i) {
    if (i) hal::uart::write(',');
    // Micrometres: units over units per metre (full steps per metre times
    // units per full step), in float (1 um in 10 m) unless they are units.
    // With settings (board::kSettings) the scale is the steps/mm setting's.
    const float per_um = board::kSettings ? float(gcode::steps_per_m(i)) * 1e-6f
                                          : float(board::Axes::steps_per_m_at(i)) *
                                                board::Axes::units_per_full_step_at(i) * 1e-6f;
    const float um = float(now[i]) / per_um;
    am::format_fixed(buf, InMicrometres<board::Axes>::value && !board::kSettings ? now[i]
                                                                                : int32_t(um < 0 ? um - 0.5f : um + 0.5f),
                     3);
    hal::uart::write(buf);
  }
  hal::uart::write_P(PSTR("|FS:"));
  hal::uart::write_u32(path::busy() ? gcode::feed_mm_per_min() : 0);
  hal::uart::write_P(PSTR(",0>\n"));
}

}  // namespace

void boot(bool by_watchdog) {
  if (by_watchdog && reset_in_motion == kMotionLost) {
    limits::fail();
    reply::alarm(3, PSTR("reset while in motion, position lost"));
  }
  reset_in_motion = 0;
}

void poll() {
  uint8_t got;
  {
    const uint8_t sreg = SREG;
    cli();
    got = asked;
    asked = 0;
    SREG = sreg;
  }
  if (got & kHold) path::hold();
  if (got & kResume) path::resume();
  if (got & kStatus) report();
}

}  // namespace realtime

// In Marlin's style (an image with both, $200=1) the bytes are a line's
// text: a host's M117 may say "Done!".
bool hal::uart::take_realtime(uint8_t c) {
  if (!board::kRealtime || reply::marlin()) return false;
  using namespace realtime;
  switch (c) {
    case '?': asked |= kStatus; return true;
    case '!': asked |= kHold; return true;
    case '~': asked |= kResume; return true;
    case 0x18:
      cli();
      hal::step_timer::halt();
      if (engine::busy()) reset_in_motion = kMotionLost;
      hal::watchdog::reset();
    default: return false;
  }
}
