// The printer codes (printer_codes.h) on the planner and the G-code side.
#include "printer_codes.h"

#include <avr/pgmspace.h>

#include "../../core/text/fixed_number.h"
#include "../../hal/avr/uart.h"
#include "../apps/cnc/gcode.h"
#include "../apps/cnc/reply.h"
#include "../engine/path.h"

namespace printer_codes {
namespace {

using Command = am::GcodePrinterCommand<board::Axes::count>;

// M201, M203: each axis given, from 1/10000 mm/s^2 or mm/s into steps, held
// within the board's limits.
void axis_limits(const Command& c) {
  const bool accel = c.code == am::GcodeCode::m201;
  for (uint8_t a = 0; a < board::Axes::count; ++a) {
    if (!(c.given & (1u << a))) continue;
    const uint32_t own = board::Axes::max_rate_at(a);
    const int32_t top = int32_t(accel ? board::kMaxAccel : own ? own : board::kMaxStepRate);
    const int32_t low = accel ? 2 : 1;
    int32_t steps = top;  // when the product overflows
    if (!am::scale_round(c.value[a], gcode::steps_per_m(a), 10000000ul, steps) || steps > top || steps < low) {
      steps = steps < low ? low : top;
      reply::info_begin();
      hal::uart::write(board::Axes::name_at(a));
      hal::uart::write_P(PSTR(" held within the board's limit"));
      reply::info_end();
    }
    path::set_axis_limit(a, accel, float(steps));
  }
}

void progress(const Command& c) {
  reply::info_begin();
  hal::uart::write_P(PSTR("Progress:"));
  if (c.given & 1) {
    hal::uart::write(' ');
    hal::uart::write_u32(uint32_t(c.value[0]));
    hal::uart::write('%');
  }
  if (c.given & 2) {
    hal::uart::write(' ');
    hal::uart::write_u32(uint32_t(c.value[1]));
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
  hal::uart::write_u32(feed ? gcode::feed_percent() : gcode::flow());
  hal::uart::write('%');
  reply::info_end();
}

}  // namespace

// M117 <text> (a printer's): the text up to a ';' comment, as an info line
// (`echo:<text>`, grbl `[MSG:<text>]`), and ok; true when the line is one.
// Its own reading: the parser would take the text for words.
bool message(const char* line) {
  while (*line == ' ' || *line == '\t') ++line;
  if ((*line & ~0x20) != 'M' || line[1] != '1' || line[2] != '1' || line[3] != '7') return false;
  line += 4;
  if (*line != ' ' && *line != '\t' && *line != '\0' && *line != ';') return false;
  if (*line == ' ' || *line == '\t') ++line;
  reply::info_begin();
  while (*line && *line != ';') hal::uart::write(uint8_t(*line++));
  reply::info_end();
  reply::ok();
  return true;
}

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
