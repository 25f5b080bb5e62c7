#include "gcode.h"

#include <avr/pgmspace.h>

#include "../../../core/motion/arc_chords.h"
#include "../../../core/text/gcode_interpreter.h"
#include "../../../hal/avr/uart.h"
#include "../../axes/axis_modes.h"
#include "../../board.h"
#include "../../engine/limits.h"
#include "../../engine/path.h"
#include "../../engine/planner.h"
#include "../../services/heater_codes.h"
#include "../../services/homing.h"
#include "../../services/printer_codes.h"
#include "gcode_axes.h"
#include "pending.h"
#include "reply.h"

namespace gcode {
namespace {

constexpr uint8_t kAxes = board::Axes::count;

// A Marlin host's G4 P is milliseconds (G4 S seconds), chosen with the
// style where it is chosen at run time (board::kProtocolSwitch); a board
// whose axes have no excitation modes refuses M350 whole.
constexpr uint8_t kDwell = board::kProtocolSwitch ? am::kDwellChosen : uint8_t(reply::kMarlin);
// Built on first use, so a board without G-code links none of it. A board
// without arcs (board::kArcs: flash) refuses G2/G3 whole (arcs_not_here),
// one without a heater its M-codes (no_heater).
using Interpreter =
    am::GcodeInterpreter<kAxes, board::kArcs, board::kHeater, kDwell, kModes, board::kHeater && board::kPrinterCodes,
                         board::kFirmwareRetract>;
Interpreter& interpreter() {
  static Interpreter instance(AxisTable<board::Axes>::value);
  return instance;
}

// The accepted line's (pending.h), until execute() has run it.
constexpr am::GcodeAction<kAxes>& action = pending::line.action;
bool pending;
int32_t coord_before[kAxes];  // program position before the pending line
uint16_t feed_percent_ = 100;  // M220 (a printer's)
float feed_scale = 1e-4f;      // of action.feed (1/10000 mm/min) to mm/min, M220's percent applied

// A feed move's F in mm/min.
float feed_of_action() { return float(action.feed) * (board::kPrinterCodes ? feed_scale : 1e-4f); }

// G2/G3: chords in position units, which are steps on the axes of a board
// with arcs, so every chord end is a step position within half a step of
// the circle and every chord's sag within kArcSag of it; each chord is a
// block for the look-ahead planner like a G1 (core/motion/arc_chords.h).
// A stepped point stays within 1.24 steps of the arc (docs/interpolation.md).
constexpr float kArcSag = 0.25f;  // steps
am::ArcChords<kAxes> arc;
bool arc_started;  // the pending arc's first chord is queued

void report_position() {
  char buf[14];
  for (uint8_t i = 0; i < kAxes; ++i) {
    if (i) hal::uart::write(' ');
    hal::uart::write(uint8_t(board::Axes::name_at(i)));
    hal::uart::write(':');
    am::format_fixed(buf, interpreter().state().axis[i].coord, 4);
    hal::uart::write(buf);
  }
  // Where the motors are at this instant, moving or not.
  int32_t now[kAxes];
  planner::positions_now(now);
  hal::uart::write_P(PSTR(" Count"));
  for (uint8_t i = 0; i < kAxes; ++i) {
    hal::uart::write(' ');
    hal::uart::write(uint8_t(board::Axes::name_at(i)));
    hal::uart::write(':');
    reply::position(now[i], board::Axes::units_per_full_step_at(i));
  }
  hal::uart::write('\n');
}


// Steps of each axis's current mode from where the planner has it to
// `target` (position units; a coil axis's step is 64 / microsteps of them),
// rounded to the nearest step: G-code and the direct MOVE agree on where
// the motors are.
planner::Move move_to(const int32_t (&target)[kAxes]) {
  planner::Move m{};
  for (uint8_t i = 0; i < kAxes; ++i) {
    const int32_t grid = board::Axes::units_for(i, 1, false);
    const int32_t units = target[i] - planner::position(i);
    m.steps[i] = (units < 0 ? units - grid / 2 : units + grid / 2) / grid;
  }
  return m;
}

// A feed beyond what the axes can do runs at what they can: said before the
// block moves.
void warn_if_held() {
  const float asked = feed_of_action(), held = path::held_feed();
  if (held < asked * 0.9999f) {
    char buf[14];
    am::format_fixed(buf, int32_t(held + 0.5f), 0);
    reply::info_begin();
    hal::uart::write_P(PSTR("F clamped to "));
    hal::uart::write(buf);
    hal::uart::write_P(PSTR(" mm/min"));
    reply::info_end();
  }
}

// A G0/G1 (accept() has checked it): one block into the look-ahead ring,
// its length and direction from the program coordinates.
bool move() {
  const planner::Move m = move_to(action.target);
  if (planner::mask_of(m.steps) == 0) return true;
  float delta_mm[kAxes];
  for (uint8_t i = 0; i < kAxes; ++i) delta_mm[i] = float(action.coord[i] - coord_before[i]) * 1e-4f;
  // bad_feed cannot come back: the interpreter refuses F <= 0 on a G1.
  if (path::add(m, delta_mm, feed_of_action(), action.rapid) == path::Added::full) return false;
  if (!action.rapid) warn_if_held();
  return true;
}

// The arc accept() has started: its next chord into the ring if it has
// room; true after the last. One chord a call, so the main loop's pump
// (which hands blocks to the engine) runs between chords. A chord's length
// in mm comes from its steps.
bool arc_chords() {
  if (arc.done()) {
    arc_started = false;
    return true;
  }
  if (!path::room()) return false;
  int32_t point[kAxes];
  arc.next(point);
  const planner::Move m = move_to(point);
  if (planner::mask_of(m.steps) == 0) return false;  // two chord ends on one step
  float delta_mm[kAxes];
  for (uint8_t i = 0; i < kAxes; ++i)
    delta_mm[i] = float(board::Axes::units_for(i, m.steps[i], false)) * 1000.0f /
                  float(AxisTable<board::Axes>::value[i].steps_per_m);
  path::add(m, delta_mm, feed_of_action(), false);
  if (!arc_started) warn_if_held();
  arc_started = true;
  return false;
}

// A heater M-code (only a board with a heater has them): the service prints
// its whole answer, M105's `ok T:...` included.
bool heater_code() {
  if (board::kHeater && !heater::run(action.heater)) return false;
  pending = false;
  return true;
}

// G28 (only a board with homing has it): the homing service says what went
// wrong; once homed, the program positions follow the machine's.
bool home() {
  const homing::Result r = homing::run(action.axes);
  if (r == homing::Result::busy) return false;
  pending = false;
  if (r == homing::Result::failed) return true;
  int32_t now[kAxes];
  planner::positions_now(now);
  interpreter().set_homed(action.axes ? action.axes : board::Endstops::axes, now);
  reply::ok();
  return true;
}

bool moves(am::GcodeActionKind kind) {
  return kind == am::GcodeActionKind::move || kind == am::GcodeActionKind::arc || kind == am::GcodeActionKind::home;
}

}  // namespace

bool claims(const char* line) {
  // G, M or N and then a number (blanks between allowed): "MOVE" and "NOP"
  // are not G-code. A comment line (';' or '(') is: answered ok.
  while (*line == ' ' || *line == '\t') ++line;
  if (*line == ';' || *line == '(') return true;
  const char c = char(*line++ & ~0x20);
  if (c != 'G' && c != 'M' && c != 'N') return false;
  while (*line == ' ' || *line == '\t') ++line;
  return (*line >= '0' && *line <= '9') || *line == '-' || *line == '+' || *line == '.';
}

bool accept(const char* line) {
  if (board::kPrinterCodes && printer_codes::message(line)) return false;
  const am::GcodeState<kAxes> before = interpreter().state();
  for (uint8_t i = 0; i < kAxes; ++i) {
    coord_before[i] = before.axis[i].coord;
  }
  if (board::kProtocolSwitch) Interpreter::set_marlin_dwell(reply::marlin());
  am::GcodeError e = interpreter().run(line, action);
  // M303 where the board leaves the autotune out (board::kAutotune).
  if (!board::kAutotune && e == am::GcodeError::none && action.kind == am::GcodeActionKind::heater &&
      action.heater.code == am::GcodeCode::m303)
    e = am::GcodeError::unsupported_code;
  if (e != am::GcodeError::none) {
    // Marlin style: a code the image does not have is Marlin's unknown
    // command, and so is a heater code on a board without a heater (the
    // m32-direct in Marlin style: a host's M105 poll must not read as a
    // firmware error).
    if (reply::marlin() && (e == am::GcodeError::unsupported_code || (!board::kHeater && e == am::GcodeError::no_heater)))
      reply::unknown_command(line);
    else
      refuse(e);
    return false;
  }
  // What the machine cannot run is refused now, with the state put back.
  const char* refusal = nullptr;
  uint8_t refusal_code = reply::code::invalid_target;
  if (action.kind == am::GcodeActionKind::move) {
    const planner::Refusal r = planner::check(move_to(action.target));
    if (r > planner::Refusal::nothing_to_do) {
      refusal = planner::refusal_text(r);
      refusal_code = reply::refusal_code(r);
    }
  } else if (action.kind == am::GcodeActionKind::home) {
    if (!board::kHoming || (action.axes & ~board::Endstops::axes)) {
      refusal = PSTR("G28 homes only axes with an endstop");
    } else if (board::kSettings && !limits::homing_enabled) {
      refusal = PSTR("homing is off ($22=0)");
      refusal_code = reply::code::homing_off;
    } else if (limits::alarm()) {
      refusal = planner::refusal_text(planner::Refusal::alarm);
      refusal_code = reply::code::alarm_lock;
    }
  }
  if (board::kArcs && action.kind == am::GcodeActionKind::arc) {
    int32_t from[kAxes];
    for (uint8_t i = 0; i < kAxes; ++i) from[i] = before.axis[i].steps;
    // The interpreter has checked radius and end point; what is left is the
    // circle within the position range and at most 65535 chords.
    if (!arc.start(from, action.target, action.plane_axis[0], action.plane_axis[1], action.centre,
                   action.clockwise, kArcSag)) {
      refusal = PSTR("arc beyond the position range or over 65535 chords");
      refusal_code = reply::code::arc_too_big;
    }
  }
  if (refusal) {
    interpreter().restore(before);
    reply::error(refusal_code, refusal);
    return false;
  }
  pending = true;
  return true;
}

void write_state() {
  const am::GcodeModal& m = interpreter().state().modal;
  // The modes' digits patched into one template line.
  static const char kTemplate[] PROGMEM = "[GC:G0 G17 G21 G90 G94 M82 F";
  char text[sizeof kTemplate];
  memcpy_P(text, kTemplate, sizeof text);
  text[5] = char('0' + uint8_t(m.motion));
  text[9] = char('7' + uint8_t(m.plane));
  text[13] = m.inches ? '0' : '1';
  text[17] = m.incremental ? '1' : '0';
  text[25] = m.e_relative ? '3' : '2';
  hal::uart::write(text);
  // F in the line's units, whole, as grbl reports it (1/10000 mm/min; an
  // inch is 25.4 mm).
  const uint32_t per_unit = m.inches ? 254000 : 10000;
  hal::uart::write_u32((uint32_t(m.feed) + per_unit / 2) / per_unit);
  hal::uart::write_P(PSTR("]\n"));
}

bool execute() {
  if (!pending) return true;
  if (action.kind == am::GcodeActionKind::heater) return heater_code();
  if (board::kPrinterCodes && action.kind == am::GcodeActionKind::printer) {
    pending = false;
    printer_codes::run(action.printer);
    return true;
  }
  // An alarm raised since the line was accepted (a hard limit under the
  // motion before it): it does not move.
  if (limits::alarm() && moves(action.kind)) {
    pending = arc_started = false;
    reply::error(reply::code::alarm_lock, planner::refusal_text(planner::Refusal::alarm));
    return true;
  }
  if (board::kHoming && action.kind == am::GcodeActionKind::home) return home();
  switch (action.kind) {
    case am::GcodeActionKind::move:
      if (!move()) return false;
      break;
    case am::GcodeActionKind::arc:  // only on a board with arcs (board::kArcs)
      if (board::kArcs && !arc_chords()) return false;
      break;
    case am::GcodeActionKind::dwell:
      if (!path::handed_over()) return false;
      path::dwell(action.dwell_ms);
      break;
    case am::GcodeActionKind::report_position:
      report_position();
      break;
    case am::GcodeActionKind::unlock:
      limits::unlock();
      break;
    case am::GcodeActionKind::enable:
      board::Axes::energise(uint8_t((1u << kAxes) - 1));
      break;
    case am::GcodeActionKind::release:
    case am::GcodeActionKind::wait:
    case am::GcodeActionKind::program_end:
      if (!path::at_rest()) return false;
      if (action.kind == am::GcodeActionKind::release) path::release();
      break;
    case am::GcodeActionKind::set_mode:
      if (!path::at_rest()) return false;
      // The interpreter checked every mode against the axis's table.
      for (uint8_t i = 0; i < kAxes; ++i)
        if (action.axes & (1u << i)) AxisModes<board::Axes>::set(board::Axes::name_at(i), action.mode[i]);
      break;
    default:  // none, set_position: nothing for the machine to do
      break;
  }
  pending = false;
  reply::ok();
  return true;
}

namespace {
template <typename Entry>
void set_steps_per_m(Entry& e, uint32_t steps_per_m) {
  e.steps_per_m = steps_per_m;
}
template <typename Entry>
void set_steps_per_m(const Entry&, uint32_t) {}  // a board without settings: never called
}  // namespace

void set_scale(uint8_t axis, uint32_t steps_per_m) { set_steps_per_m(AxisTable<board::Axes>::value[axis], steps_per_m); }

void rescale() { interpreter().rescale(); }

uint32_t steps_per_m(uint8_t axis) { return AxisTable<board::Axes>::value[axis].steps_per_m; }

uint32_t feed_mm_per_min() { return uint32_t(interpreter().state().modal.feed) / 10000u; }

void set_feed_percent(uint16_t percent) {
  feed_percent_ = percent;
  feed_scale = float(percent) * 1e-6f;
}
uint16_t feed_percent() { return feed_percent_; }
void set_flow(uint16_t percent) { interpreter().set_flow(percent); }
uint16_t flow() { return interpreter().flow(); }
am::GcodeRetraction retraction() { return interpreter().retraction(); }
void set_retraction(const am::GcodeRetraction& settings) { interpreter().set_retraction(settings); }

}  // namespace gcode
