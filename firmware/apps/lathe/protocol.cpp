// The lathe's line protocol (contract in docs/lathe.md, "Over the UART").
//
//   G33 Z<end> K<pitch> | P<tpi> [D<starts> E<start>]
//       a spindle-synchronised pass from here to Z (mm, absolute; towards
//       the chuck, -Z, cuts a right-hand thread with the spindle forward),
//       pitch K in mm or P in threads per inch (both exact: 13 TPI is
//       25400/13 um); start E (0..D-1) of a D-start thread.
//   G0 Z<end> [F<mm/min>]   a positioning move (absolute mm).
//   ENCODER C<lines> E<1|4> the spindle encoder: one channel counted once
//                           per line, or quadrature x4.
//   STOP                    disengage(): a pass stops, a move decelerates.
//   WAIT                    answered once the pass or move has ended (the
//                           lines after it wait too).
//   ? (or STATUS)           the status line, then ok.
// A motion line while a pass or move runs is refused (`error: busy`): the
// sender asks `?` until `state=idle`. Words follow the G-code grammar
// (core/text/gcode_parser.h: parse_gcode reads them, so its checks apply);
// lines come from core/text/line_reader.h.
#include "protocol.h"

#include <avr/pgmspace.h>

#include "../../../core/lathe/ratio.h"
#include "../../../core/text/command_parser.h"
#include "../../../core/text/fixed_number.h"
#include "../../../core/text/gcode_parser.h"
#include "../../../core/text/line_reader.h"
#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "answer.h"
#include "leadscrew.h"

namespace protocol {
namespace {

using Reader = am::LineReader<64>;
Reader reader;
bool tainted;  // bytes were lost: refuse lines until one ends with the ring empty
bool waiting;  // a WAIT is answered when the leadscrew is idle

using answer::error;
using answer::ok;

const char* parse_error_text(am::GcodeError e) {
  switch (e) {
    case am::GcodeError::bad_character: return PSTR("expected a word letter");
    case am::GcodeError::bad_comment: return PSTR("comment not closed");
    case am::GcodeError::unsupported_word: return PSTR("unsupported word letter");
    case am::GcodeError::bad_number: return PSTR("bad number");
    case am::GcodeError::out_of_range: return PSTR("number out of range");
    case am::GcodeError::bad_line_number: return PSTR("bad N word");
    case am::GcodeError::modal_group_conflict: return PSTR("two codes of one modal group");
    case am::GcodeError::repeated_word: return PSTR("word given twice");
    default: return PSTR("unsupported G or M code");
  }
}

const char* refusal_text(leadscrew::Refusal r) {
  switch (r) {
    case leadscrew::Refusal::busy: return PSTR("busy");
    case leadscrew::Refusal::bad_start: return PSTR("E must be below D");
    case leadscrew::Refusal::too_steep:
      return board::kServoLeadscrew ? PSTR("64 or more counts per count") : PSTR("16 or more steps per count");
    case leadscrew::Refusal::phase_range: return PSTR("start phase out of range");
    case leadscrew::Refusal::limit: return PSTR("limit switch hit");
    case leadscrew::Refusal::bad_rate: return PSTR("feed must be above 0");
    default: return PSTR("length out of range");
  }
}

// mm (1/10000) <-> leadscrew steps, exactly from the board's rationals:
// steps per um = counts.num pitch.den / (counts.den pitch.num).
constexpr uint32_t kStepsNum = board::kLeadscrewCounts.num * board::kLeadscrewPitch.den;
constexpr uint32_t kStepsDen = board::kLeadscrewCounts.den * board::kLeadscrewPitch.num * 10;

// Any parsed length (|v| <= 214748.3647 mm) is at most 54.1 M steps: it fits.
int32_t mm_to_steps(int32_t length) {
  int32_t steps = 0;
  am::scale_round(length, kStepsNum, kStepsDen, steps);
  return steps;
}

bool whole(const am::GcodeBlock& b, char letter, int32_t lo, int32_t hi, int32_t& out) {
  const int32_t v = b.get(letter);
  if (v % am::kLengthScale != 0) return false;
  out = v / am::kLengthScale;
  return out >= lo && out <= hi;
}

constexpr uint32_t bit(char c) { return am::gcode_letter_bit(c); }
const char kUnusedWord[] PROGMEM = "word not used here";

void thread(const am::GcodeBlock& b) {
  if (b.words & ~(bit('Z') | bit('K') | bit('P') | bit('D') | bit('E'))) return error(kUnusedWord);
  if (!b.has('Z') || b.has('K') == b.has('P')) return error(PSTR("G33 needs Z and K or P"));
  if (leadscrew::busy()) return error(refusal_text(leadscrew::Refusal::busy));
  int32_t starts = 1, start = 0;
  if (b.has('D') && !whole(b, 'D', 1, 255, starts)) return error(PSTR("D must be 1..255"));
  if (b.has('E') && !whole(b, 'E', 0, 254, start)) return error(PSTR("E must be 0..254"));
  const int32_t pitch = b.get(b.has('K') ? 'K' : 'P');
  if (pitch <= 0) return error(PSTR("pitch must be above 0"));
  const int32_t end = mm_to_steps(b.get('Z'));
  // The servo's passes start from where the last motion was meant to end
  // (its slip carried into the pass), the stepper's from where it is.
  const int32_t here = board::kServoLeadscrew ? leadscrew::reference() : leadscrew::position();
  if (end == here) return error(PSTR("Z is here"));
  // K: um = K / 10; P: um = 25400 / (P / 10000).
  const am::Pitch p = b.has('K') ? am::Pitch{uint32_t(pitch), 10} : am::Pitch{254000000ul, uint32_t(pitch)};
  const am::ThreadRequest request{p, uint8_t(starts), end < here ? am::Hand::right : am::Hand::left};
  const am::GearRatio g = am::gear_ratio_exact(leadscrew::machine(), request);
  if (g.status != am::RatioStatus::exact) return error(PSTR("ratio not exact in 32 bits"));
  const leadscrew::Refusal r =
      leadscrew::engage(g.ratio, g.reversed, end < here ? here - end : end - here, uint8_t(start), uint8_t(starts));
  if (r != leadscrew::Refusal::none) return error(refusal_text(r));
  ok();
}

void position_move(const am::GcodeBlock& b) {
  if (b.words & ~(bit('Z') | bit('F'))) return error(kUnusedWord);
  if (!b.has('Z')) return error(PSTR("G0 needs Z"));
  const int32_t end = mm_to_steps(b.get('Z'));
  int32_t rate = int32_t(board::kLeadscrewMaxRate);
  if (b.has('F')) {
    // mm/min -> steps/s
    if (b.get('F') <= 0 || !am::scale_round(b.get('F'), kStepsNum, kStepsDen * 60, rate) || rate == 0)
      return error(refusal_text(leadscrew::Refusal::bad_rate));
  }
  const leadscrew::Refusal r = leadscrew::move_to(end, uint32_t(rate));
  if (r != leadscrew::Refusal::none) return error(refusal_text(r));
  ok();
}

void encoder(const am::GcodeBlock& b) {
  if (b.words & ~(bit('C') | bit('E'))) return error(kUnusedWord);
  int32_t lines, edges;
  if (!b.has('C') || !b.has('E') || !whole(b, 'C', 1, 16383, lines) || !whole(b, 'E', 1, 4, edges) ||
      (edges != 1 && edges != 4))
    return error(PSTR("ENCODER needs C1..16383, E1 or E4"));
  if (board::kServoLeadscrew && edges == 4) return error(PSTR("E4 needs INT0, the servo's"));
  if (!leadscrew::set_encoder(edges == 4, uint16_t(lines))) return error(refusal_text(leadscrew::Refusal::busy));
  ok();
}

void status() {
  static const char kStates[] PROGMEM = "idle\0    moving\0  armed\0   catching\0locked";
  static const char kStops[] PROGMEM = "none\0     done\0     length\0   limit\0    stopped\0  overspeed";
  hal::uart::write_P(PSTR("state="));
  hal::uart::write_P(kStates + 9 * uint8_t(leadscrew::state()));
  const int32_t steps = leadscrew::position();
  hal::uart::write_P(PSTR(" z="));
  hal::uart::write_i32(steps);
  int32_t um = 0;  // positions stay within the parser's range (see above): it fits
  am::scale_round(steps, kStepsDen / 10, kStepsNum, um);
  char mm[13];
  am::format_fixed(mm, um, 3);
  hal::uart::write_P(PSTR(" mm="));
  hal::uart::write(mm);
  hal::uart::write_P(PSTR(" err="));
  hal::uart::write_i32(leadscrew::following_error());
  hal::uart::write_P(PSTR(" rpm="));
  hal::uart::write_i32(leadscrew::spindle_rpm());
  hal::uart::write_P(PSTR(" count="));
  hal::uart::write_i32(leadscrew::spindle_count());
  hal::uart::write_P(PSTR(" lost="));
  hal::uart::write_u32(leadscrew::lost_counts());
  hal::uart::write_P(PSTR(" last="));
  hal::uart::write_P(kStops + 10 * uint8_t(leadscrew::last_stop()));
  if (board::kServoLeadscrew && !leadscrew::busy()) {  // the last motion's, once the motor stands
    hal::uart::write_P(PSTR(" slip="));
    hal::uart::write_i32(leadscrew::last_slip());
  }
  hal::uart::write('\n');
  ok();
}

// "G33" (any case, blanks after G allowed) at p: p moves past it.
bool g33(const char*& p) {
  const char* q = p;
  if (am::detail::upper(*q) != 'G') return false;
  ++q;
  while (am::detail::blank(*q)) ++q;
  int32_t n;
  bool point;
  if (am::parse_fixed(q, 0, n, point) != am::NumberStatus::ok || point || n != 33) return false;
  p = q;
  return true;
}

const char kNotLathe[] PROGMEM = "not a lathe command";

void on_line(const char* p) {
  while (am::detail::blank(*p)) ++p;
  if (!*p) return ok();
  if ((p[0] == '?' && !p[1]) || am::detail::keyword(p, "STATUS")) return status();
  if (am::detail::keyword(p, "STOP")) {
    leadscrew::disengage();
    return ok();
  }
  if (am::detail::keyword(p, "WAIT")) {
    waiting = true;
    return;
  }
  const bool is_encoder = am::detail::keyword(p, "ENCODER");
  const bool is_thread = !is_encoder && g33(p);
  am::GcodeBlock b;
  const am::GcodeError e = am::parse_gcode<false>(p, b);
  if (e != am::GcodeError::none) return error(parse_error_text(e));
  for (uint8_t g = 0; g < am::kGcodeGroups; ++g) {
    const am::GcodeCode c = b.code[g];
    if (c != am::GcodeCode::none && !(g == uint8_t(am::GcodeGroup::motion) && c == am::GcodeCode::g0 &&
                                      !is_encoder && !is_thread))
      return error(kNotLathe);
  }
  if (is_encoder) return encoder(b);
  if (is_thread) return thread(b);
  if (b.group(am::GcodeGroup::motion) == am::GcodeCode::g0) return position_move(b);
  if (b.words) return error(kNotLathe);
  ok();  // a comment or an empty block
}

}  // namespace

void banner() { answer::banner(); }

void poll() {
  if (waiting) {
    if (leadscrew::busy()) return;
    waiting = false;
    ok();
  }
  while (hal::uart::available()) {
    if (hal::uart::overrun()) tainted = true;
    const Reader::Line line = reader.feed(char(hal::uart::read()));
    if (line == Reader::Line::none) continue;
    if (tainted) {
      tainted = hal::uart::available();
      error(PSTR("serial overrun, line dropped"));
    } else if (line == Reader::Line::too_long) {
      error(PSTR("line too long (max 64)"));
    } else if (line == Reader::Line::bad_byte) {
      error(PSTR("bad byte in line"));
    } else {
      on_line(reader.text());
    }
    return;  // one line per poll: the leadscrew's control runs between lines
  }
}

}  // namespace protocol
