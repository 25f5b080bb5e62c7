#include "protocol.h"

#include <avr/pgmspace.h>

#include "../../../core/text/command_parser.h"
#include "../../../core/text/line_reader.h"
#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "../../axes/axis_modes.h"
#include "../../engine/path.h"
#include "../../engine/planner.h"
#include "gcode.h"
#include "reply.h"

namespace protocol {
namespace {

using Reader = am::LineReader<80>;
Reader reader;
am::Command command;
// What was accepted and waits for its turn: `command`, or the G-code line's
// action (gcode.h).
enum class Waiting : uint8_t { nothing, command, gcode };
Waiting waiting;
// Set when received bytes were lost. The gap lies somewhere after the bytes
// still in the receive ring, so every line completed from then on is refused
// until one ends with the ring empty: a line spliced across the gap can never
// run as a different, valid command.
bool tainted;

using reply::ok;
using reply::error;

const char* parse_error_text(am::ParseError e) {
  switch (e) {
    case am::ParseError::unknown_command: return PSTR("unknown command");
    case am::ParseError::bad_word: return PSTR("bad word (expected letter and number)");
    case am::ParseError::bad_number: return PSTR("bad number");
    case am::ParseError::out_of_range: return PSTR("number out of range");
    case am::ParseError::duplicate_word: return PSTR("word given twice");
    case am::ParseError::missing_axis: return PSTR("MOVE needs an axis word");
    case am::ParseError::two_axes: return PSTR("MODE takes one axis");
    case am::ParseError::unexpected_word: return PSTR("word not allowed here");
    default:  // bad_mode (none and empty never come here)
      return PSTR("mode must be 0, 1, 2, 16, 32 or 64");
  }
}

void warn_clamped(char word, uint32_t value) {
  hal::uart::write_P(PSTR("warning: "));
  hal::uart::write(uint8_t(word));
  hal::uart::write_P(PSTR(" clamped to "));
  hal::uart::write_u32(value);
  hal::uart::write('\n');
}


// The longest move: positions are kept in 1/64 full step for coil axes,
// and 2^24 * 64 still fits the 32-bit counters.
constexpr int32_t kMaxMoveSteps = 16777216;

// Tries to run the waiting command; false while it must keep waiting.
bool execute(const am::Command& c) {
  switch (c.kind) {
    case am::CommandKind::move: {
      planner::Move move{};
      for (uint8_t k = 0; k < c.axis_count; ++k) {
        const int8_t axis = board::Axes::index_of(c.axes[k]);
        if (axis < 0) {
          error(PSTR("no such axis on this board"));
          return true;
        }
        if (c.axis_steps[k] > kMaxMoveSteps || c.axis_steps[k] < -kMaxMoveSteps) {
          error(PSTR("move too long (max 16777216 steps)"));
          return true;
        }
        move.steps[axis] = c.axis_steps[k];
      }
      if (!path::handed_over() || !path::ready_for(move)) return false;
      switch (planner::check(move)) {
        case planner::Refusal::none: break;
        case planner::Refusal::nothing_to_do: ok(); return true;
        case planner::Refusal::position_range: error(PSTR("move would leave the position range")); return true;
        case planner::Refusal::timer_axis_not_alone:
          error(PSTR("the hardware-timed axis moves alone"));
          return true;
      }
      planner::Ramp ramp{(c.given & am::kGivenRate) ? c.rate : board::kDefaultRate,
                         (c.given & am::kGivenAccel) ? c.accel : board::kDefaultAccel};
      switch (planner::check_ramp(ramp)) {
        case planner::RampError::none: break;
        case planner::RampError::zero_speed: error(PSTR("speed must be above 0")); return true;
        case planner::RampError::zero_accel: error(PSTR("acceleration must be above 0")); return true;
        case planner::RampError::rate_above_tick: error(PSTR("speed above the timer clock")); return true;
        case planner::RampError::accel_too_low: error(PSTR("acceleration too low for the timer")); return true;
      }
      const uint8_t clamped = planner::clamp(move, ramp);
      if (clamped & planner::kClampedRate) warn_clamped('F', ramp.rate);
      if (clamped & planner::kClampedAccel) warn_clamped('A', ramp.accel);
      path::add_direct(move, ramp);
      ok();
      return true;
    }
    case am::CommandKind::position:
      if (!path::at_rest()) return false;
      hal::uart::write_P(PSTR("pos"));
      for (uint8_t i = 0; i < board::Axes::count; ++i) {
        hal::uart::write(' ');
        hal::uart::write(uint8_t(board::Axes::name_at(i)));
        hal::uart::write(':');
        reply::position(planner::position(i), board::Axes::units_per_full_step_at(i));
      }
      hal::uart::write('\n');
      ok();
      return true;
    case am::CommandKind::release:
      if (!path::at_rest()) return false;
      path::release();
      ok();
      return true;
    case am::CommandKind::wait:
      if (!path::at_rest()) return false;
      ok();
      return true;
    case am::CommandKind::mode:
      // Like POS: only an idle axis changes mode (docs/modes.md).
      if (!path::at_rest()) return false;
      switch (AxisModes<board::Axes>::set(c.axis, uint8_t(c.steps))) {
        case ModeResult::ok: ok(); break;
        case ModeResult::no_axis: error(PSTR("no such axis on this board")); break;
        case ModeResult::no_modes: error(PSTR("axis has no excitation modes")); break;
        default: error(PSTR("mode not available on this axis")); break;
      }
      return true;
  }
  return true;
}

void on_line(Reader::Line line) {
  if (tainted) {
    tainted = hal::uart::available();
    error(PSTR("serial overrun, line dropped"));
  } else if (line == Reader::Line::too_long) {
    error(PSTR("line too long (max 80 characters)"));
  } else if (line == Reader::Line::bad_byte) {
    error(PSTR("control or non-ASCII byte in line"));
  } else {
    if (board::kGcode && gcode::claims(reader.text())) {
      if (gcode::accept(reader.text())) waiting = Waiting::gcode;
      return;
    }
    const am::ParseError e = am::parse_command(reader.text(), command);
    if (e == am::ParseError::none) {
      waiting = Waiting::command;
    } else if (e == am::ParseError::empty) {
      ok();  // spaces and tabs only: nothing to do, but every line is answered
    } else {
      error(parse_error_text(e));
    }
  }
}

}  // namespace

void banner() { reply::banner(); }

void poll() {
  path::pump();
  if (waiting != Waiting::nothing) {
    const bool done = waiting == Waiting::command ? execute(command) : (!board::kGcode || gcode::execute());
    if (!done) return;
    waiting = Waiting::nothing;
  }
  while (waiting == Waiting::nothing && hal::uart::available()) {
    if (hal::uart::overrun()) tainted = true;
    const Reader::Line line = reader.feed(char(hal::uart::read()));
    if (line != Reader::Line::none) on_line(line);
  }
  // Nothing more on its way for now: the path may start on what it holds.
  if (waiting == Waiting::nothing && !hal::uart::available() && reader.between_lines()) path::start();
}

}  // namespace protocol
