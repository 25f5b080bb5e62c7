#include "protocol.h"

#include <avr/pgmspace.h>

#include "../../../core/text/command_parser.h"
#include "../../../core/text/gcode_parser.h"
#include "../../../core/text/line_reader.h"
#include "../../../hal/avr/step_timer.h"
#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "../../axes/axis_modes.h"
#include "../../engine/clock.h"
#include "../../engine/limits.h"
#include "../../engine/path.h"
#include "../../engine/planner.h"
#include "../../services/heater.h"
#include "../../services/settings.h"
#include "gcode.h"
#include "pending.h"
#include "reply.h"

namespace pending {
Line line;
}  // namespace pending

namespace protocol {
namespace {

using reply::ok;
using reply::error;
using reply::marlin;
namespace code = reply::code;

using Reader = am::LineReader<kLineCapacity>;
Reader reader;
// The waiting command shares its RAM with a G-code action (pending.h); a
// board without G-code keeps its own, and the linker drops the union.
am::Command own_command;
constexpr am::Command& command = board::kGcode ? pending::line.command : own_command;
// What was accepted and waits for its turn: `command`, the G-code line's
// action (gcode.h), or Marlin's M400 (motion to end).
// A settings change (`$N=value`, `$RST=$`, or one of Marlin's settings
// codes) waits for the machine at rest with its line still in the reader:
// its text from `setting_text` (after the `$`, or after the M-code), the
// M-code in `setting_code` (0 for a `$` line).
enum class Waiting : uint8_t { nothing, command, gcode, setting };
Waiting waiting;
char* setting_text;
uint16_t setting_code;
// Set when received bytes were lost. The gap lies somewhere after the bytes
// still in the receive ring, so every line completed from then on is refused
// until one ends with the ring empty: a line spliced across the gap can never
// run as a different, valid command.
bool tainted;

// Marlin: the last line number accepted (M110 sets it), when the waiting
// line is due its next `busy: processing`, and M112's halt.
int32_t last_line;
uint32_t busy_at;
bool halted;
constexpr uint32_t kBusyPeriodMs = 2000;  // Marlin's DEFAULT_KEEPALIVE_INTERVAL

void hold(Waiting w) {
  waiting = w;
  if (marlin()) busy_at = clock::now() + clock::ms(kBusyPeriodMs);
}

using E = am::GcodeError;
// A refusal whose text G-code has too: on a board with G-code its table's
// (gcode::refuse), so the image holds the text once.
__attribute__((always_inline)) inline void refuse(E shared, uint8_t grbl_code, const char* progmem_reason) {
  if (board::kGcode) return gcode::refuse(shared);
  error(grbl_code, progmem_reason);
}

void parse_error(am::ParseError e) {
  switch (e) {
    case am::ParseError::unknown_command:
      if (marlin()) return reply::unknown_command(reader.text());
      return error(code::unsupported, PSTR("unknown command"));
    case am::ParseError::bad_word: return refuse(E::bad_character, code::expected_letter, PSTR("expected a word letter"));
    case am::ParseError::bad_number: return refuse(E::bad_number, code::bad_number, PSTR("bad number"));
    case am::ParseError::out_of_range: return refuse(E::out_of_range, code::out_of_range, PSTR("number out of range"));
    case am::ParseError::duplicate_word: return refuse(E::repeated_word, code::repeated_word, PSTR("word given twice"));
    case am::ParseError::missing_axis:
      return refuse(E::missing_axis_word, code::no_axis_words, PSTR("code needs an axis word"));
    case am::ParseError::two_axes: return error(code::mode_one_axis, PSTR("MODE takes one axis"));
    case am::ParseError::unexpected_word: return error(code::unused_words, PSTR("word not allowed here"));
    default:  // bad_mode (none and empty never come here)
      return refuse(E::bad_mode, code::bad_mode, PSTR("mode must be 0, 1, 2, 16, 32 or 64"));
  }
}

void no_such_axis() { refuse(E::no_such_axis, code::unsupported, PSTR("no such axis on this board")); }

void warn_clamped(char word, uint32_t value) {
  reply::info_begin();
  hal::uart::write(uint8_t(word));
  hal::uart::write_P(PSTR(" clamped to "));
  hal::uart::write_u32(value);
  reply::info_end();
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
          no_such_axis();
          return true;
        }
        if (c.axis_steps[k] > kMaxMoveSteps || c.axis_steps[k] < -kMaxMoveSteps) {
          error(code::move_too_long, PSTR("move too long (max 16777216 steps)"));
          return true;
        }
        move.steps[axis] = c.axis_steps[k];
      }
      if (!path::handed_over() || !path::ready_for(move)) return false;
      const planner::Refusal refusal = planner::check(move);
      switch (refusal) {
        case planner::Refusal::none: break;
        case planner::Refusal::nothing_to_do: ok(); return true;
        default: error(reply::refusal_code(refusal), planner::refusal_text(refusal)); return true;
      }
      planner::Ramp ramp{(c.given & am::kGivenRate) ? c.rate : board::kDefaultRate,
                         (c.given & am::kGivenAccel) ? c.accel : board::kDefaultAccel};
      switch (planner::check_ramp(ramp)) {
        case planner::RampError::none: break;
        case planner::RampError::zero_speed: error(code::zero_speed, PSTR("speed must be above 0")); return true;
        case planner::RampError::zero_accel: error(code::zero_accel, PSTR("acceleration must be above 0")); return true;
        case planner::RampError::rate_above_tick:
          error(code::rate_above_tick, PSTR("speed above the timer clock"));
          return true;
        case planner::RampError::accel_too_low:
          error(code::accel_too_low, PSTR("acceleration too low for the timer"));
          return true;
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
        case ModeResult::no_axis: no_such_axis(); break;
        case ModeResult::no_modes:
          refuse(E::axis_has_no_modes, code::no_modes, PSTR("axis has no excitation modes"));
          break;
        default: refuse(E::mode_not_available, code::mode_unavailable, PSTR("mode not available on this axis")); break;
      }
      return true;
  }
  return true;
}

char* skip_blanks(char* p) {
  while (*p == ' ' || *p == '\t') ++p;
  return p;
}

// A whole number (optional '-', at most 9 digits) at p, which moves past it.
bool read_int(char*& p, int32_t& value) {
  const bool negative = *p == '-';
  if (negative) ++p;
  uint8_t digits = 0;
  int32_t v = 0;
  for (; *p >= '0' && *p <= '9'; ++p, ++digits) v = v * 10 + (*p - '0');
  value = negative ? -v : v;
  return digits > 0 && digits <= 9;
}

// M<code> as the first word at p (which then moves past it), or -1.
int32_t m_code(char*& p) {
  char* q = p;
  int32_t m;
  if ((*q | 0x20) != 'm' || !read_int(++q, m) || (*q != '\0' && *q != ' ' && *q != '\t')) return -1;
  p = q;
  return m;
}

// Marlin: the line is not run; the host sends it again from `Resend:`.
void resend(const char* progmem_reason) {
  reply::error_begin();
  hal::uart::write_P(progmem_reason);
  hal::uart::write_P(PSTR(", Last Line: "));
  hal::uart::write_i32(last_line);
  hal::uart::write_P(PSTR("\nResend: "));
  hal::uart::write_i32(last_line + 1);
  hal::uart::write('\n');
  ok();
}

// Marlin's `N<n> <line>*<checksum>`: the line without number and checksum,
// or nullptr when it was refused with a resend request. A line without N
// runs unchecked (a host typing by hand); a line with N needs its checksum
// (Marlin: "No Checksum with line number") and the next number in turn,
// except M110, which sets it.
char* numbered(char* line) {
  char* p = skip_blanks(line);
  const char* end;
  const am::Checksum sum = am::split_checksum(line, end);
  int32_t n;
  if ((*p | 0x20) != 'n' || !(++p, read_int(p, n))) {
    if (sum == am::Checksum::absent) return line;
    resend(PSTR("No Line Number with checksum"));
    return nullptr;
  }
  if (sum != am::Checksum::ok) {
    resend(sum == am::Checksum::absent ? PSTR("No Checksum with line number") : PSTR("checksum mismatch"));
    return nullptr;
  }
  *const_cast<char*>(end) = '\0';
  p = skip_blanks(p);
  char* code = p;
  if (n != last_line + 1 && m_code(code) != 110) {
    resend(PSTR("Line Number is not Last Line Number+1"));
    return nullptr;
  }
  last_line = n;
  return p;
}

// M115's capabilities: M155 where there is a heater, M500..M503 where the
// settings are (the printer's M500 stores the heater's gains only). One
// text per image, the others folded away.
#define AM_M115(temp, eeprom)                                                                                   \
  PSTR("FIRMWARE_NAME:avrmotion " AVRMOTION_VERSION " SOURCE_CODE_URL:local PROTOCOL_VERSION:1.0 MACHINE_TYPE:" \
       AVRMOTION_BOARD_NAME " EXTRUDER_COUNT:1\nCap:AUTOREPORT_TEMP:" temp "\nCap:EEPROM:" eeprom              \
       "\nCap:EMERGENCY_PARSER:0\n")
void firmware_info() {
  hal::uart::write_P(board::kHeater ? (board::kSettings ? AM_M115("1", "1") : AM_M115("1", "0"))
                                    : (board::kSettings ? AM_M115("0", "1") : AM_M115("0", "0")));
}
#undef AM_M115

void refuse_halted() { error(code::heater, PSTR("Printer halted (M112), reset to restart")); }

// The heater's output off now, on a board that has one (board::Heater is
// declared only there).
template <typename H>
auto heater_output_off(int) -> decltype(H::Pwm::set(0)) {
  H::Pwm::set(0);
}
template <typename H>
void heater_output_off(long) {}

// M112: steps stop at once (the step timer with them), coils and drivers
// off, the heater off (its target 0 from then on); every line from then on
// is refused until reset.
void halt() {
  hal::step_timer::stop();
  board::Axes::release();
  if (board::kHeater) heater::set_target(0);
  heater_output_off<board::Heater>(0);
  halted = true;
  refuse_halted();
}

// Marlin's own codes, the protocol's: true when the line was one of them.
bool marlin_code(char* p) {
  switch (m_code(p)) {
    case 110: {  // M110 [N<n>]: the next line is n + 1
      p = skip_blanks(p);
      int32_t n;
      if ((*p | 0x20) == 'n' && (++p, read_int(p, n))) last_line = n;
      ok();
      return true;
    }
    case 112:
      halt();
      return true;
    case 115:
      firmware_info();
      ok();
      return true;
    default:
      return false;
  }
}

// The settings' Marlin codes (docs/settings.md), in either style, on a board
// with settings: M92, M201, M203, M205 set, M500 stores, M501 reloads,
// M502 restores the defaults, M503 reports; like `$N=`, once at rest.
bool settings_code(char* p) {
  const int32_t m = m_code(p);
  if (m != 92 && m != 201 && m != 203 && m != 205 && (m < 500 || m > 503)) return false;
  setting_text = p;
  setting_code = uint16_t(m);
  hold(Waiting::setting);
  return true;
}

const char kNotHere[] PROGMEM = "not in this image";

// grbl's '$' lines: `$` help, `$I` build info, `$G` the parser state, `$X`
// unlock (the alarm of a hard limit, a failed homing or a soft reset in
// motion: docs/realtime.md), `$H` homing (G28, on a board with homing); the
// settings commands (and realtime bytes sent as a line) are refused with
// grbl's "not recognized or supported" until they exist.
bool grbl_system(char* p) {
  p = skip_blanks(p);
  const char c = *p;
  if (c == '?' || c == '!' || c == '~') {
    error(code::bad_system_command, kNotHere);
    return true;
  }
  if (c != '$') return false;
  const char what = char(p[1] & ~0x20);
  if (board::kSettings && (what == 'R' || (p[1] >= '0' && p[1] <= '9'))) {
    setting_text = p + 1;
    setting_code = 0;
    hold(Waiting::setting);  // settings::change() once at rest
    return true;
  }
  if (p[1] == '\0') {
    hal::uart::write_P(board::kSettings ? PSTR("[HLP:$ $$ $x=val $RST=$ $I $G $X]\n") : PSTR("[HLP:$ $I $G $X]\n"));
  } else if (board::kSettings && p[1] == '$' && p[2] == '\0') {
    settings::list();
  } else if (p[2] != '\0' || !(what == 'I' || what == 'X' || (board::kGcode && what == 'G') ||
                                (board::kHoming && what == 'H'))) {
    error(code::bad_system_command, kNotHere);
    return true;
  } else if (what == 'H') {  // G28: every axis with an endstop, its answer when homed
    if (gcode::accept("G28")) hold(Waiting::gcode);
    return true;
  } else if (what == 'X') {
    limits::unlock();
    reply::info_P(PSTR("Caution: Unlocked"));
  } else if (what == 'I') {
    hal::uart::write_P(PSTR("[VER:1.1h.avrmotion-" AVRMOTION_VERSION ":" AVRMOTION_BOARD_NAME "]\n[OPT:,"));
    hal::uart::write_u32(board::kPathBlocks);
    hal::uart::write(',');
    hal::uart::write_u32(kReceiveRing);
    hal::uart::write_P(PSTR("]\n"));
  } else {
    gcode::write_state();
  }
  ok();
  return true;
}

void on_line(Reader::Line kind) {
  // After M112 (the image with both styles: here rather than poll()'s own loop).
  if (board::kProtocolSwitch && halted) return refuse_halted();
  if (tainted) {
    tainted = hal::uart::available();
    // Marlin: the host sends the line again.
    const char* const reason = PSTR("serial overrun, line dropped");  // one copy for both styles
    if (marlin()) return resend(reason);
    return error(code::overrun, reason);
  }
  if (kind == Reader::Line::too_long) return error(code::line_overflow, PSTR("line too long (max 96 characters)"));
  if (kind == Reader::Line::bad_byte) {
    const char* const reason = PSTR("control or non-ASCII byte in line");
    if (marlin()) return resend(reason);
    return error(code::bad_byte, reason);
  }
  char* line = reader.text();
  if (marlin()) {
    line = numbered(line);
    if (!line || marlin_code(line)) return;
  } else if (!board::kProtocolSwitch && grbl_system(line)) {
    return;
  }
  // With both styles in the image, grbl's `$` lines in either (the way back
  // from Marlin's: `$200=0`).
  if (board::kProtocolSwitch && grbl_system(line)) return;
  if (board::kSettings && settings_code(line)) return;
  if (board::kGcode && gcode::claims(line)) {
    if (gcode::accept(line)) hold(Waiting::gcode);
    return;
  }
  const am::ParseError e = board::kCommands ? am::parse_command(line, command) : am::ParseError::unknown_command;
  if (e == am::ParseError::none) {
    hold(Waiting::command);
  } else if (e == am::ParseError::empty) {
    ok();  // spaces and tabs only: nothing to do, but every line is answered
  } else {
    parse_error(e);
  }
}

bool done_waiting() {
  switch (waiting) {
    case Waiting::command: return !board::kCommands || execute(command);
    default:
      if (board::kSettings && waiting == Waiting::setting) {
        if (!path::at_rest()) return false;
        if (setting_code)
          settings::marlin(setting_code, setting_text);
        else
          settings::change(setting_text);
        return true;
      }
      return !board::kGcode || gcode::execute();  // M400 too: the interpreter's wait
  }
}

}  // namespace

void banner() {
  hal::uart::write_P(marlin() ? PSTR("start\necho:") : PSTR("Grbl 1.1h ['$' for help]\n[MSG:"));
  hal::uart::write_P(PSTR("avrmotion " AVRMOTION_VERSION " board=" AVRMOTION_BOARD_NAME " mcu=" AVRMOTION_MCU_NAME
                          " f_cpu="));
  hal::uart::write_u32(F_CPU);
  reply::info_end();
}

void poll() {
  if (!board::kProtocolSwitch && marlin() && halted) {
    while (hal::uart::available()) {
      const Reader::Line line = reader.feed(char(hal::uart::read()));
      if (line != Reader::Line::none) refuse_halted();
    }
    return;
  }
  path::pump();
  if (waiting != Waiting::nothing) {
    if (!done_waiting()) {
      // Marlin's host keep-alive: a host that hears nothing for long
      // takes the line as lost.
      if (marlin() && clock::due(busy_at, clock::ms(kBusyPeriodMs))) hal::uart::write_P(PSTR("busy: processing\n"));
      return;
    }
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
