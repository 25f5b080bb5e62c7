// The printer codes (printer_codes.h) on the planner and the G-code side.
#include "printer_codes.h"

#include <avr/pgmspace.h>

#include "../../hal/avr/uart.h"
#include "../apps/cnc/gcode.h"
#include "../apps/cnc/reply.h"
#include "../engine/path.h"

namespace printer_codes {
namespace {

using Command = am::GcodePrinterCommand<board::Axes::count>;

void write_whole(uint32_t v) { hal::uart::write_u32(v); }

// `echo:<code> <axis> clamped to <v> <unit>`: v in the unit, whole.
void say_clamped(const Command& c, uint8_t axis, float v) {
  reply::info_begin();
  hal::uart::write_P(c.code == am::GcodeCode::m201 ? PSTR("M201 ") : PSTR("M203 "));
  hal::uart::write(board::Axes::name_at(axis));
  hal::uart::write_P(PSTR(" clamped to "));
  write_whole(uint32_t(v + 0.5f));
  hal::uart::write_P(c.code == am::GcodeCode::m201 ? PSTR(" mm/s^2") : PSTR(" mm/s"));
  reply::info_end();
}

// M201, M203: each axis given, from 1/10000 mm/s^2 or mm/s into steps,
// within the board's limits.
void axis_limits(const Command& c) {
  const bool accel = c.code == am::GcodeCode::m201;
  for (uint8_t a = 0; a < board::Axes::count; ++a) {
    if (!(c.given & (1u << a))) continue;
    const float per_mm = float(gcode::steps_per_m(a)) * 1e-3f;
    const uint32_t own = board::Axes::max_rate_at(a);
    const float top = accel ? float(board::kMaxAccel) : float(own ? own : board::kMaxStepRate);
    const float low = accel ? 2.0f : 1.0f;
    float steps = float(c.value[a]) * 1e-4f * per_mm;
    if (steps > top || steps < low) {
      steps = steps > top ? top : low;
      say_clamped(c, a, steps / per_mm);
    }
    if (accel)
      path::set_max_accel(a, steps);
    else
      path::set_max_rate(a, steps);
  }
}

void progress(const Command& c) {
  reply::info_begin();
  hal::uart::write_P(PSTR("Progress:"));
  if (c.given & 1) {
    hal::uart::write(' ');
    write_whole(uint32_t(c.value[0]));
    hal::uart::write('%');
  }
  if (c.given & 2) {
    hal::uart::write(' ');
    write_whole(uint32_t(c.value[1]));
    hal::uart::write_P(PSTR(" min left"));
  }
  reply::info_end();
}

// M220, M221: set, or say (Marlin's lines).
void percent(const Command& c) {
  const bool feed = c.code == am::GcodeCode::m220;
  if (c.given & 1) {
    const uint16_t p = uint16_t(c.value[0]);
    if (feed)
      gcode::set_feed_percent(p);
    else
      gcode::set_flow(p);
    return;
  }
  reply::info_begin();
  hal::uart::write_P(feed ? PSTR("FR:") : PSTR("E0 Flow: "));
  write_whole(feed ? gcode::feed_percent() : gcode::flow());
  hal::uart::write('%');
  reply::info_end();
}

}  // namespace

void run(const Command& c) {
  switch (c.code) {
    case am::GcodeCode::m73:
      progress(c);
      break;
    case am::GcodeCode::m201:
    case am::GcodeCode::m203:
      axis_limits(c);
      break;
    case am::GcodeCode::m204:  // slots P T R S; S for P and T where they are not given
      for (uint8_t k = 0; k < 3; ++k) {
        const uint8_t slot = (c.given & (1u << k)) ? k : k < 2 && (c.given & 8) ? 3 : 0xFF;
        if (slot != 0xFF) path::set_path_accel(path::PathAccel(k), float(c.value[slot]) * 1e-4f);
      }
      break;
    case am::GcodeCode::m205:
      if (c.given) path::set_junction_um(uint32_t(c.value[0] + 5) / 10);
      break;
    default:
      percent(c);
      break;
  }
  reply::ok();
}

}  // namespace printer_codes
