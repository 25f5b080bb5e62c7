// G-code interpreter front end: the modal state of docs/gcode.md and the step
// from one parsed block (gcode_parser.h) to one action for the machine, a
// move, an arc, a dwell and so on, with every target already in steps.
//
// Contract
//   GcodeInterpreter<N>(axes) serves a board with the N axes `axes[]` (the
//   array must outlive the interpreter): their letters, M350 modes and scale
//   in steps per metre. A word for any other axis letter is no_such_axis.
//   GcodeInterpreter<N, false> has no arcs: a G2/G3 motion is arcs_not_here
//   and none of the arc arithmetic is linked (a machine that cannot run arcs
//   keeps its flash). GcodeInterpreter<N, A, false> has no heater: every
//   heater M-code is no_heater and their checks are not linked.
//   GcodeInterpreter<N, A, H, true> reads G4's words as Marlin does (a
//   printer host's dialect): P milliseconds, S seconds (S wins if both).
//   GcodeInterpreter<N, A, H, kDwellChosen> reads them one way or the
//   other as set_marlin_dwell() last said (an image with both protocol
//   styles, chosen at run time; NGC's until then).
//   GcodeInterpreter<N, A, H, D, false> serves axes without excitation
//   modes (step/dir drivers set their microsteps in hardware): M350 is then
//   unsupported_code, as in a Marlin built without microstep pins, and none
//   of its checks is linked. GcodeInterpreter<N, A, H, D, M, false> (the
//   default: as H) has no printer codes (M73 M201 M203 M204 M205 M220
//   M221: unsupported_code) and no flow. GcodeInterpreter<N, A, H, D, M,
//   P, true> has the firmware retraction (gcode_retraction.h: G10 G11 M207
//   M208); without it (the default) they are unsupported_code and nothing
//   of it is linked or kept in RAM.
//
//   execute(block, action) applies one block. On GcodeError::none the state
//   has moved on (modes, feed, G92 offsets, position) and `action` says what
//   the machine has to do; on any error the state is exactly what it was and
//   `action` is unspecified: every check is made on a copy, committed last.
//   At most one action per line (multiple_actions otherwise). run(line,
//   action) parses and executes a NUL-terminated line.
//
//   Positions. Per axis the state keeps (state().axis[i])
//     coord   the program position (what the G-code's numbers refer to),
//             in 1/10000 mm (kLengthScale), |coord| <= 214748.3647 mm;
//     offset  the G92 offset, in steps: steps = length_to_steps(coord) + offset;
//     steps   the machine position, in steps: where the targets so far lead.
//   An absolute word sets coord to the value (inch words converted to
//   1/10000 mm, rounded); an incremental one adds to coord, so rounding to
//   steps never accumulates over a run of G91 moves. Targets are rounded
//   half away from zero. A line whose target coord or steps would leave the
//   int32 range is target_out_of_range. E follows its own distance mode:
//   G90/G91 set it with the others (as Marlin does), M82/M83 then set E alone.
//   G92 sets coord to the values given and keeps steps (only the offset
//   changes, the machine does not move).
//
//   Actions (GcodeAction::kind):
//     move             G0/G1 (or axis words in that motion mode): target[]
//                      steps for every axis, rapid, feed (1/10000 mm/min)
//     arc              G2/G3: target[], feed, clockwise, plane_axis[] (board
//                      axis indices of the plane's first and second axis and
//                      of its normal, kNoAxis if the board has none), centre[]
//                      (centre minus start, steps, per plane axis),
//                      centre_length[] (the same in 1/10000 mm) and radius
//                      (1/10000 mm). end == start (I/J form) is a full circle.
//     dwell            G4 P<seconds> (MarlinDwell: P<ms> or S<seconds>):
//                      dwell_ms (rounded)
//     set_position     G92: nothing moves; the changed offsets are in the state
//     report_position  M114: print state().axis[i].coord (and .steps)
//     enable, release  M17; M18 or M84 (every axis)
//     wait             M400: the answer waits until every move has ended
//     set_mode         M350: mode[i] for every axis in `axes`
//     program_end      M2/M30 (modes back to power-up, see below)
//     home             G28: home the axes in `axes` (every axis that can
//                      be homed when 0); the words' values are not used
//                      and nothing changes here: the machine puts the
//                      homed axes where they are with set_homed()
//     unlock           M999: end an alarm (the machine's business)
//     heater           M104 M105 M108 M109 M155 M301 M303: `heater` says
//                      what (GcodeHeaterCommand, see Heater codes below)
//     none             a line that only sets modes or F, or is empty
//   `axes` has bit i set for every axis the line named. After every accepted
//   line target[] holds the machine position (steps) and coord[] the program
//   position (1/10000 mm) of every axis: a move's length in mm comes from
//   coord[] minus the previous coord[], without a conversion back from steps.
//
//   Arcs. The centre of an I/J/K arc is start + offsets; the start radius is
//   |offsets|, and the end point's distance from the centre may differ from
//   it by at most the tolerance: max(0.005 mm, 0.1 % of the radius), at most
//   0.5 mm (arc_radius_mismatch beyond). An R arc takes the short way for
//   R > 0 and the long way (more than 180 degrees) for R < 0; the centre is
//   computed in integers (64-bit products, isqrt), to about 0.1 um for sane
//   geometry. An R smaller than half the chord by up to the tolerance is
//   taken as a half circle (centre at the chord's middle), beyond that it is
//   arc_radius_too_small. Helices: the other axes move linearly.
//
//   Power-up modes: G0, G17, G90, G21, G94, M82, no feed (a feed move before
//   the first F is bad_feed), all positions and offsets 0. M2/M30 restore
//   G0, G17, G90, M82 and keep units, F, positions and offsets.
//
//   Heater codes (M104 M105 M106 M107 M108 M109 M155 M301 M303 M500:
//   action heater) and printer codes (M73 M201 M203 M204 M205 M220 M221:
//   action printer): their words and ranges are in gcode_heater_codes.h and
//   gcode_printer_codes.h; each is alone on its line and changes no state.
//
//   Flow (set_flow(), M221's, the machine's business to call): every later
//   move's E steps are its distance's times flow / 100, rounded half away
//   from zero, and the difference goes into E's G92 offset, so the program
//   position is what the program said and the machine position is what ran.
//
//   Check order (the error for a line with several faults): parser errors
//   left to right, then no_such_axis, the F word, axis_conflict,
//   multiple_actions, missing words, unused_word, then the action's values.
#pragma once
#include <stdint.h>

#include "fixed_number.h"
#include "gcode_arithmetic.h"
#include "gcode_parser.h"
#include "gcode_state.h"

namespace am {

template <bool Retract>
struct GcodeRetractionSlot {
  GcodeRetraction value;
};
template <>
struct GcodeRetractionSlot<false> {};

// MarlinDwell: 0 (false) NGC's G4, 1 (true) Marlin's, kDwellChosen either at run time.
constexpr uint8_t kDwellChosen = 2;

template <uint8_t N, bool Arcs = true, bool Heater = true, uint8_t MarlinDwell = 0, bool Modes = true,
          bool Printer = Heater, bool Retract = false>
class GcodeInterpreter : private GcodeRetractionSlot<Retract> {  // empty without Retract: no RAM
  static_assert(N >= 1 && N <= 8, "one bit per axis in GcodeAction::axes");

 public:
  explicit GcodeInterpreter(const GcodeAxis (&axes)[N]) : axes_(axes), board_letters_(0) {
    for (uint8_t i = 0; i < N; ++i) board_letters_ |= gcode_letter_bit(axes[i].letter);
    reset();
  }

  // Power-up state: modes, feed, positions and offsets.
  void reset() {
    state_.modal = GcodeModal{Motion::rapid, Plane::xy, false, false, false, 0};
    for (uint8_t i = 0; i < N; ++i) state_.axis[i] = GcodeAxisState{0, 0, 0};
    clear_retracted(*this);
  }

  const GcodeState<N>& state() const { return state_; }
  // Puts back a state taken from state(): for a caller that refuses an
  // accepted line's action after all (the machine cannot run it), so the
  // line changes nothing.
  void restore(const GcodeState<N>& state) { state_ = state; }
  const GcodeAxis& axis(uint8_t i) const { return axes_[i]; }

  // M221's flow, percent (a printer's): each later move's E steps are its
  // distance's times flow / 100, rounded half away from zero; the
  // difference goes into E's offset, so the program position stays.
  void set_flow(uint16_t percent) { flow_ = percent; }
  uint16_t flow() const { return flow_; }

  // Homing has put the axes in mask `axes` at machine positions steps[]
  // (G28): no G92 offset is left on them and their program positions follow
  // from the steps.
  void set_homed(uint8_t axes, const int32_t (&steps)[N]) {
    GcodeAxisState* a = state_.axis;
    const GcodeAxis* ax = axes_;
    const int32_t* s = steps;
    for (uint8_t i = 0; i < N; ++i, axes = uint8_t(axes >> 1), ++a, ++ax, ++s) {
      if (!(axes & 1)) continue;
      a->steps = *s;
      a->offset = 0;
      steps_to_length(*s, ax->steps_per_m, a->coord);
    }
  }

  // The axes' scale (steps_per_m of the table) has changed, at rest: the
  // machine positions and G92 offsets (steps) stay, the program positions
  // follow (core/board/settings.h: a steps/mm setting).
  void rescale() {
    for (uint8_t i = 0; i < N; ++i) {
      GcodeAxisState& a = state_.axis[i];
      int32_t from_offset, c;
      if (gcode_detail::add_checked(a.steps, -a.offset, from_offset) &&
          steps_to_length(from_offset, axes_[i].steps_per_m, c))
        a.coord = c;
    }
  }

  // Board axis index of an (upper-case) letter, kNoAxis if absent.
  uint8_t index_of(char letter) const {
    for (uint8_t i = 0; i < N; ++i)
      if (axes_[i].letter == letter) return i;
    return kNoAxis;
  }

  GcodeError run(const char* line, GcodeAction<N>& action) {
    GcodeBlock block;
    const GcodeError e = parse_gcode<Printer, Retract>(line, block);
    return e != GcodeError::none ? e : execute(block, action);
  }

  GcodeError execute(const GcodeBlock& b, GcodeAction<N>& a);

  // G4 as Marlin reads it from now on, or as NGC (MarlinDwell kDwellChosen).
  static void set_marlin_dwell(bool marlin) { marlin_dwell_ = marlin; }

  // The firmware retraction's settings and state (Marlin's defaults
  // without Retract); settings put in keep the state (ignored without it).
  using Retraction = GcodeRetraction;
  Retraction retraction() const { return retraction_of(*this); }
  void set_retraction(const Retraction& r) { set_retraction_of(*this, r); }

 private:
  static bool marlin_dwell_;
  static bool marlin_dwell() { return MarlinDwell == 1 || (MarlinDwell == kDwellChosen && marlin_dwell_); }
  GcodeError arc(const GcodeBlock& b, const GcodeModal& m, GcodeAction<N>& a) const;
  GcodeError heater(const GcodeBlock& b, GcodeAction<N>& a) const;
  GcodeError printer(const GcodeBlock& b, GcodeAction<N>& a) const;
  // The retraction lives only in an interpreter with Retract (the base
  // GcodeRetractionSlot: no RAM, no constructor code without it): each step
  // has an overload for the empty slot, never called (execute() asks
  // Retract first).
  template <bool R>
  using RetractionSlot = GcodeRetractionSlot<R>;
  GcodeError retract(const GcodeBlock& b, GcodeAction<N>& a, bool out, RetractionSlot<true>& slot);
  GcodeError retract_settings(const GcodeBlock& b, bool recover, RetractionSlot<true>& slot);
  GcodeError retract(const GcodeBlock&, GcodeAction<N>&, bool, RetractionSlot<false>&) {
    return GcodeError::unsupported_code;
  }
  GcodeError retract_settings(const GcodeBlock&, bool, RetractionSlot<false>&) { return GcodeError::unsupported_code; }
  static void clear_retracted(RetractionSlot<true>& slot) { slot.value.retracted = false; }
  static void clear_retracted(RetractionSlot<false>&) {}
  static Retraction retraction_of(const RetractionSlot<true>& slot) { return slot.value; }
  static Retraction retraction_of(const RetractionSlot<false>&) { return Retraction(); }
  static void set_retraction_of(RetractionSlot<true>& slot, Retraction r) {
    r.retracted = slot.value.retracted;
    slot.value = r;
  }
  static void set_retraction_of(RetractionSlot<false>&, const Retraction&) {}
  // M221's flow on E's target `steps` from `st` (its offset into `offset`);
  // false beyond the position range.
  [[gnu::noinline]] bool flow(const GcodeAxisState& st, int32_t& steps, int32_t& offset) const {
    int32_t delta, flowed;
    return flow_ == 100 || (gcode_detail::add_checked(steps, -st.steps, delta) &&
                            scale_round(delta, flow_, 100, flowed) && gcode_detail::add_checked(st.steps, flowed, steps) &&
                            gcode_detail::add_checked(st.offset, flowed - delta, offset));
  }
  // An action that moves nothing: the positions as they are.
  [[gnu::noinline]] GcodeError hold_position(GcodeAction<N>& a, GcodeActionKind kind) const {
    for (uint8_t i = 0; i < N; ++i) {
      a.coord[i] = state_.axis[i].coord;
      a.target[i] = state_.axis[i].steps;
    }
    a.axes = 0;
    a.kind = kind;
    return GcodeError::none;
  }

  // steps = length_to_steps(coord) + offset on axis i; false beyond int32.
  bool machine_steps(uint8_t i, int32_t coord, int32_t offset, int32_t& steps) const {
    return length_to_steps(coord, axes_[i].steps_per_m, steps) && gcode_detail::add_checked(steps, offset, steps);
  }

  const GcodeAxis* axes_;
  uint32_t board_letters_;  // gcode_letter_bit() of every axis letter
  GcodeState<N> state_;
  uint16_t flow_ = 100;  // M221: percent of every E move's steps (a printer's)
};

template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
bool GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::marlin_dwell_ = false;

template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
GcodeError GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::execute(const GcodeBlock& b,
                                                                                          GcodeAction<N>& a) {
  using namespace gcode_detail;
  if (Retract) {
    const GcodeCode nm = b.group(GcodeGroup::non_modal), mc = b.group(GcodeGroup::machine);
    if (nm == GcodeCode::g10 || nm == GcodeCode::g11) return retract(b, a, nm == GcodeCode::g10, *this);
    if (mc == GcodeCode::m207 || mc == GcodeCode::m208) {
      hold_position(a, GcodeActionKind::none);
      return retract_settings(b, mc == GcodeCode::m208, *this);
    }
  }
  if (b.group(GcodeGroup::machine) >= GcodeCode::m104) return heater(b, a);
  constexpr uint32_t kArcWords =
      gcode_letter_bit('I') | gcode_letter_bit('J') | gcode_letter_bit('K') | gcode_letter_bit('R');
  const uint32_t words = b.words;
  if (words & kGcodeAxisLetters & ~board_letters_) return GcodeError::no_such_axis;
  const bool axis_words = (words & kGcodeAxisLetters) != 0;
  // The next state is built in m, a.coord[], a.target[] and offset[]; state_
  // is only written once the whole line has been accepted.
  GcodeModal m = state_.modal;

  // Modes, in the order the rest of the line sees them.
  const GcodeCode units = b.group(GcodeGroup::units);
  const GcodeCode plane = b.group(GcodeGroup::plane);
  const GcodeCode distance = b.group(GcodeGroup::distance);
  const GcodeCode extruder = b.group(GcodeGroup::extruder);
  const GcodeCode motion = b.group(GcodeGroup::motion);
  if (units != GcodeCode::none) m.inches = units == GcodeCode::g20;
  if (plane != GcodeCode::none) m.plane = Plane(uint8_t(plane) - uint8_t(GcodeCode::g17));
  if (distance != GcodeCode::none) m.incremental = m.e_relative = distance == GcodeCode::g91;
  if (extruder != GcodeCode::none) m.e_relative = extruder == GcodeCode::m83;
  if (motion != GcodeCode::none) m.motion = Motion(uint8_t(motion) - uint8_t(GcodeCode::g0));
  if (words & gcode_letter_bit('F')) {
    const int32_t f = b.get('F');
    if (f < 0) return GcodeError::bad_feed;
    if (!to_length(f, m.inches, m.feed)) return GcodeError::out_of_range;
  }

  // Who takes the axis words; one action per line.
  const GcodeCode non_modal = b.group(GcodeGroup::non_modal);
  const GcodeCode machine = b.group(GcodeGroup::machine);
  const GcodeCode stop = b.group(GcodeGroup::stop);
  const bool dwell = non_modal == GcodeCode::g4;
  const bool set_position = non_modal == GcodeCode::g92;
  const bool home = non_modal == GcodeCode::g28;
  if (!Modes && machine == GcodeCode::m350) return GcodeError::unsupported_code;
  const bool set_mode = Modes && machine == GcodeCode::m350;
  if ((set_position || set_mode || home) && motion != GcodeCode::none) return GcodeError::axis_conflict;
  const bool move = axis_words && !set_position && !set_mode && !home;
  const uint8_t actions = uint8_t((non_modal != GcodeCode::none) + (machine != GcodeCode::none) +
                                  (stop != GcodeCode::none) + move);
  if (actions > 1) return GcodeError::multiple_actions;
  const bool arc_mode = m.motion >= Motion::arc_cw;

  // Required words, then unused ones.
  const bool marlin_g4 = marlin_dwell();
  const uint32_t kDwellWords = gcode_letter_bit('P') | (marlin_g4 ? gcode_letter_bit('S') : 0);
  if (dwell && !(words & kDwellWords)) return GcodeError::missing_dwell_time;
  if (((set_position || set_mode) && !axis_words) || (arc_mode && actions == 0 && (words & kArcWords)))
    return GcodeError::missing_axis_word;
  uint32_t used = gcode_letter_bit('N') | gcode_letter_bit('F') | kGcodeAxisLetters;
  if (dwell) used |= kDwellWords;
  if (move && arc_mode) {
    const uint16_t o = plane_offsets(m.plane);
    const uint32_t offset_words = gcode_letter_bit(char(o)) | gcode_letter_bit(char(o >> 8));
    const bool r = (words & gcode_letter_bit('R')) != 0;
    const bool offsets = (words & offset_words) != 0;
    if (!r && !offsets) return GcodeError::missing_arc_words;
    if (r && offsets) return GcodeError::arc_mixed_form;
    used |= offset_words | gcode_letter_bit('R');
  }
  if (words & ~used) return GcodeError::unused_word;
  if (move && m.motion != Motion::rapid && m.feed <= 0) return GcodeError::bad_feed;

  // The axis words (pointers walked in step: indexing costs a multiply per
  // array on the AVR). Offsets change only with G92, into offset[].
  int32_t offset[N];
  uint8_t named = 0;
  uint8_t bit = 1;
  const GcodeAxis* ax = axes_;
  const GcodeAxisState* st = state_.axis;
  int32_t* coord = a.coord;
  int32_t* steps = a.target;
  int32_t* off = offset;
  for (uint8_t i = 0; i < N; ++i, bit = uint8_t(bit << 1), ++ax, ++st, ++coord, ++steps, ++off) {
    *coord = st->coord;
    *steps = st->steps;
    if (Printer) *off = st->offset;
    const char letter = ax->letter;
    if (!b.has(letter)) continue;
    named |= bit;
    if (home) continue;
    const int32_t w = b.get(letter);
    if (set_mode) {
      const uint8_t mode = mode_bit(w);
      if (mode == 0) return GcodeError::bad_mode;
      if (ax->modes == 0) return GcodeError::axis_has_no_modes;
      if (!(ax->modes & mode)) return GcodeError::mode_not_available;
      a.mode[i] = mode <= kModeHalf ? uint8_t(mode >> 1) : uint8_t(mode << 1);
      continue;
    }
    int32_t len, t;
    if (!to_length(w, m.inches, len)) return GcodeError::target_out_of_range;
    if (set_position) {
      if (!length_to_steps(len, ax->steps_per_m, t) || !add_checked(*steps, -t, *off))
        return GcodeError::target_out_of_range;
    } else if (((letter == 'E' ? m.e_relative : m.incremental) && !add_checked(*coord, len, len)) ||
               !length_to_steps(len, ax->steps_per_m, t) || !add_checked(t, st->offset, *steps)) {
      return GcodeError::target_out_of_range;
    }
    if (Printer && letter == 'E' && !set_position && !flow(*st, *steps, *off)) return GcodeError::target_out_of_range;
    *coord = len;
  }

  // The action.
  a.axes = named;
  a.rapid = m.motion == Motion::rapid;
  a.feed = m.feed;
  GcodeActionKind kind = GcodeActionKind::none;
  if (dwell) {
    // 1/10000 s, or Marlin's P in 1/10000 ms (its S in seconds wins).
    const bool ms = marlin_g4 && !b.has('S');
    const int32_t p = b.get(ms ? 'P' : marlin_g4 ? 'S' : 'P');
    if (p < 0) return GcodeError::out_of_range;
    a.dwell_ms = ms ? (uint32_t(p) + 5000) / 10000 : (uint32_t(p) + 5) / 10;
    kind = GcodeActionKind::dwell;
  } else if (set_position) {
    kind = GcodeActionKind::set_position;
  } else if (home) {
    kind = GcodeActionKind::home;
    named = 0;  // nothing to commit
  } else if (set_mode) {
    kind = GcodeActionKind::set_mode;
  } else if (machine != GcodeCode::none) {
    kind = machine == GcodeCode::m17    ? GcodeActionKind::enable
           : machine == GcodeCode::m114 ? GcodeActionKind::report_position
           : machine == GcodeCode::m400 ? GcodeActionKind::wait
           : machine == GcodeCode::m999 ? GcodeActionKind::unlock
                                        : GcodeActionKind::release;
  } else if (stop != GcodeCode::none) {
    m.motion = Motion::rapid;
    m.plane = Plane::xy;
    m.incremental = m.e_relative = false;
    kind = GcodeActionKind::program_end;
  } else if (move) {
    kind = GcodeActionKind::move;
    if (arc_mode) {
      if (!Arcs) return GcodeError::arcs_not_here;
      const GcodeError e = arc(b, m, a);
      if (e != GcodeError::none) return e;
      kind = GcodeActionKind::arc;
    }
  }
  a.kind = kind;

  // Commit.
  state_.modal = m;
  GcodeAxisState* out = state_.axis;
  bit = 1;
  for (uint8_t i = 0; i < N; ++i, ++out, bit = uint8_t(bit << 1)) {
    if (!(named & bit)) continue;
    out->coord = a.coord[i];
    out->steps = a.target[i];
    if (set_position || Printer) out->offset = offset[i];
  }
  return GcodeError::none;
}

}  // namespace am

// GcodeInterpreter::arc(), heater(), printer() and retract(), apart (one
// concern a file).
#include "gcode_arc_words.h"
#include "gcode_heater_codes.h"
#include "gcode_printer_codes.h"
#include "gcode_retraction.h"
